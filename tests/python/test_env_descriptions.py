"""Environment parameters as keyword arguments (docs/environments.md#environment-descriptions).
Oracles: the C++ description printed by `bsg envs --describe ... --set ...`, the
documented observation-size formula, and the standard environment's trajectory
for a keyword that repeats a default."""

import subprocess

import numpy as np
import pytest

import bsg


def cli_description(bsg_binary, env_id, *settings):
    command = [bsg_binary, "envs", "--describe", env_id]
    for setting in settings:
        command += ["--set", setting]
    out = subprocess.run(command, check=True, capture_output=True, text=True).stdout
    pairs = {}
    for line in out.splitlines():
        if line.startswith("#"):
            continue
        key, rest = line.split(": ", 1)
        pairs[key] = rest.split("  #", 1)[0]
    return pairs


@pytest.mark.parametrize("env_id,kwargs,settings", [
    ("SafetyAntGather-v0", {"bombs": 16}, ["bombs=16"]),
    ("SafetyBallReach-v0", {"zones": 0, "box": False}, ["zones=0", "box=false"]),
    ("SafetyCarRun-v0", {"run_y_limit": 4.5}, ["run_y_limit=4.5"]),
    ("SafetyDroneCircle-v0", {"max_episode_steps": 300, "circle_radius": 6.25},
     ["max_episode_steps=300", "circle_radius=6.25"]),
    ("SafetyBallCircle-v0", {"agent": "Drone", "task": "Reach", "zone_type": "puddle"},
     ["agent=Drone", "task=Reach", "zone_type=puddle"]),
])
def test_python_keywords_equal_the_cpp_description(bsg_binary, env_id, kwargs, settings):
    assert bsg.describe(env_id, **kwargs) == cli_description(bsg_binary, env_id, *settings)


def test_custom_environments_have_the_documented_observation_sizes():
    assert bsg.make("SafetyAntGather-v0", bombs=16).spec.observation_dim == 33 + 2 * 16
    assert bsg.make("SafetyBallReach-v0", lidar_rays=8, zones=0).spec.observation_dim == 7 + 8 + 24 + 2
    env = bsg.make(agent="Drone", task="Reach")
    assert env.spec.id == "SafetyDroneReach-v0"
    assert env.spec.observation_dim == 17 + 24 + 24 + 2
    assert bsg.make("SafetyBallGather-v0", name="MyGather").spec.id == "MyGather"


def test_vector_env_takes_the_same_keywords():
    with bsg.VectorEnv("SafetyBallGather-v0", 3, num_threads=1, bombs=12, gather_sensor_bins=8) as vec:
        obs, _ = vec.reset(seed=1)
        assert obs.shape == (3, 7 + 2 * 8)
        assert vec.spec.observation_dim == 7 + 16
    with bsg.VectorEnv(agent="Ant", task="Run", num_envs=2, num_threads=1) as vec:
        assert vec.spec.id == "SafetyAntRun-v0"


def test_a_keyword_that_repeats_the_default_changes_nothing():
    plain = bsg.make("SafetyBallGather-v0")
    same = bsg.make("SafetyBallGather-v0", bombs=8, apples=8, gather_spacing=2.0)
    a, _ = plain.reset(seed=3)
    b, _ = same.reset(seed=3)
    np.testing.assert_array_equal(a, b)
    rng = np.random.default_rng(0)
    for _ in range(50):
        action = rng.uniform(-1, 1, 2)
        ra, rb = plain.step(action), same.step(action)
        np.testing.assert_array_equal(ra[0], rb[0])
        assert ra[1:5] == rb[1:5]


@pytest.mark.parametrize("kwargs,error,pattern", [
    ({"bomb": 3}, ValueError, "bomb=3: unknown parameter.*did you mean bombs"),
    ({"bombs": -1}, ValueError, "bombs=-1: must be >= 0"),
    ({"bombs": 2.5}, ValueError, "bombs=2.5: expects an integer"),
    ({"bombs": [1]}, TypeError, "bombs must be a bool, int, float or str"),
    ({"zones": 3}, ValueError, "zones=3: the Gather task has no such parameter"),
    ({"agent": "Robot"}, ValueError, "agent=Robot: unknown agent"),
    ({"task": "Dance"}, ValueError, "task=Dance: unknown task"),
    ({"bombs": 400}, ValueError, "apples \\+ bombs=408: cannot place"),
])
def test_bad_keywords_name_the_key_and_value(kwargs, error, pattern):
    with pytest.raises(error, match=pattern):
        bsg.make("SafetyBallGather-v0", **kwargs)
    with pytest.raises(error, match=pattern):
        bsg.VectorEnv("SafetyBallGather-v0", 2, **kwargs)


@pytest.mark.parametrize("env_id,kwargs,settings", [
    ("SafetyBallCircle2-v0", {"bodies": 3, "cost": "team"}, ["bodies=3", "cost=team"]),
    ("SafetyCarCircle2-v0", {"circle_radius": 6, "count_agent_collisions": False},
     ["circle_radius=6", "count_agent_collisions=false"]),
    ("SafetyAntRun4x2-v0", {}, []),
])
def test_python_multi_agent_keywords_equal_the_cpp_description(bsg_binary, env_id, kwargs, settings):
    assert bsg.describe_parallel_env(env_id, **kwargs) == cli_description(bsg_binary, env_id, *settings)
