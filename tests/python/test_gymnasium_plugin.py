"""Scripts that only call gymnasium.make(env_id), as CleanRL's do (docs/python.md#registration):
Gymnasium's "module:id" form, bsg:bsg/<id>, imports bsg and makes the environment under every
supported version; and an installed bsg's plugin entry point (python/entry_points.txt, which
`cmake --install` puts in bsg's dist-info) registers the ids while Gymnasium 0.28 and 0.29 are
imported, so that bsg/<id> works without the prefix (1.x loads no plugins). Each runs in a fresh
interpreter that never imports bsg itself. Oracle: Gymnasium's own make and registry."""

import os
import pathlib
import subprocess
import sys

from gymnasium_import import import_gymnasium

gymnasium = import_gymnasium()

import pytest  # noqa: E402

import bsg  # noqa: E402  (this process's; the scripts import their own)

ENTRY_POINTS = pathlib.Path(__file__).resolve().parents[2] / "python" / "entry_points.txt"
IS_1X = int(gymnasium.__version__.split(".")[0]) >= 1
EXPECTED = [gymnasium.__version__, "GymnasiumEnv", str(bsg.make("SafetyBallCircle-v0").spec.observation_dim),
            "True"]

SCRIPT = """
import sys
import gymnasium
assert "bsg" not in sys.modules or PLUGIN, "bsg was imported before gymnasium.make"
env = gymnasium.make(ENV_ID)
obs, info = env.reset(seed=0)
obs, reward, terminated, truncated, info = env.step(env.action_space.sample())
import bsg
assert isinstance(env.unwrapped, bsg.GymnasiumEnv) and isinstance(env.unwrapped, gymnasium.Env)
vector = bsg.VectorEnv("SafetyBallCircle-v0", 2, api="gymnasium")
assert isinstance(vector, gymnasium.vector.VectorEnv)
print(gymnasium.__version__, type(env.unwrapped).__name__, obs.shape[0], "cost" in info)
"""


def run_script(env_id, plugin, extra_path=()):
    environment = dict(os.environ)
    environment["PYTHONPATH"] = os.pathsep.join([*map(str, extra_path), *(p for p in sys.path if p)])
    script = f"ENV_ID = {env_id!r}\nPLUGIN = {plugin!r}\n" + SCRIPT
    return subprocess.run([sys.executable, "-c", script], env=environment, capture_output=True,
                          text=True, timeout=120)


def test_the_module_prefix_imports_bsg_for_gymnasium_make():
    result = run_script("bsg:bsg/SafetyBallCircle-v0", plugin=False)
    assert result.returncode == 0, result.stderr
    assert result.stdout.split() == EXPECTED


@pytest.mark.skipif(IS_1X, reason="Gymnasium 1.x loads no plugins (the bsg: prefix serves there)")
def test_an_installed_bsgs_entry_point_registers_while_gymnasium_is_imported(tmp_path):
    dist_info = tmp_path / "bsg-0.1.0.dist-info"
    dist_info.mkdir()
    (dist_info / "METADATA").write_text("Metadata-Version: 2.1\nName: bsg\nVersion: 0.1.0\n")
    (dist_info / "entry_points.txt").write_text(ENTRY_POINTS.read_text())
    result = run_script("bsg/SafetyBallCircle-v0", plugin=True, extra_path=[tmp_path])
    assert result.returncode == 0, result.stderr
    assert result.stdout.split() == EXPECTED
    assert "plugin" not in result.stderr and "Error" not in result.stderr, result.stderr
    # Without the entry point the same script fails as CleanRL's did: the namespace is unknown.
    without = run_script("bsg/SafetyBallCircle-v0", plugin=False)
    assert without.returncode != 0 and "bsg" in without.stderr
