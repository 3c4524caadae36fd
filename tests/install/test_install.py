"""The installed bsg as a user meets it.

`cmake --install` of the build into a temporary prefix; then, from a folder
that has nothing to do with the source tree, the installed `bsg` trains on a
run file there (finding the installed configs) and lists the environments; an
out-of-tree CMake project (consumer/) finds the package with find_package(bsg),
links bsg::envs and steps SafetyAntRun-v0; the same program built from the
pkg-config file does too; and both print exactly what the same source built in
tree against the build's own library prints.

Run by ctest (tests/install/CMakeLists.txt), which sets BSG_BUILD_DIR,
BSG_IN_TREE_STEP_ANT_RUN and BSG_SANITIZE.
"""

import json
import os
import pathlib
import shutil
import subprocess
import tempfile

import pytest

BUILD_DIR = pathlib.Path(os.environ.get("BSG_BUILD_DIR", ""))
IN_TREE_STEP_ANT_RUN = os.environ.get("BSG_IN_TREE_STEP_ANT_RUN", "")
SANITIZE = os.environ.get("BSG_SANITIZE", "OFF") == "ON"
CONSUMER_SOURCE = pathlib.Path(__file__).resolve().parent / "consumer"
SANITIZER_FLAGS = "-fsanitize=address,undefined"


def user_environment():
    """The caller's environment without BSG_CONFIGS, so only the install is found."""
    environment = dict(os.environ)
    environment.pop("BSG_CONFIGS", None)
    environment.setdefault("OMPI_ALLOW_RUN_AS_ROOT", "1")
    environment.setdefault("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
    if SANITIZE:
        environment["ASAN_OPTIONS"] = "detect_leaks=0"  # Open MPI's own allocations
    return environment


def run(command, cwd=None, env=None):
    """Runs `command`; fails the test with its output if it exits non-zero."""
    result = subprocess.run(command, cwd=cwd, env=env or user_environment(), capture_output=True, text=True,
                            timeout=600)
    assert result.returncode == 0, (f"{' '.join(map(str, command))} exited {result.returncode}\n"
                                    f"stdout:\n{result.stdout}\nstderr:\n{result.stderr}")
    return result.stdout


@pytest.fixture(scope="module")
def scratch():
    """A fresh folder under the system's temporary folder, far from the source tree."""
    if not (BUILD_DIR / "CMakeCache.txt").exists():
        pytest.fail(f"BSG_BUILD_DIR={BUILD_DIR} is not a CMake build folder (run this through ctest)")
    folder = pathlib.Path(tempfile.mkdtemp(prefix="bsg_install_test_"))
    yield folder
    shutil.rmtree(folder, ignore_errors=True)


@pytest.fixture(scope="module")
def prefix(scratch):
    prefix = scratch / "prefix"
    run(["cmake", "--install", str(BUILD_DIR), "--prefix", str(prefix)])
    return prefix


@pytest.fixture(scope="module")
def user_folder(scratch):
    folder = scratch / "user"
    folder.mkdir()
    return folder


def test_install_lays_out_program_configs_headers_and_packages(prefix):
    for relative in ("bin/bsg", "share/bsg/configs/algorithms/lag-trpo.yaml",
                     "share/bsg/configs/envs/SafetyAntRun-v0.yaml", "include/bsg/envs/env.h",
                     "include/bsg/common/run_config.h", "include/bsg/algos/training/trainer.h",
                     "include/bsg/envs/physics/world.h", "lib/cmake/bsg/bsgConfig.cmake",
                     "lib/cmake/bsg/bsgConfigVersion.cmake", "lib/cmake/bsg/bsgTargets.cmake", "lib/pkgconfig/bsg.pc",
                     "lib/libbsg_envs.a", "lib/libbsg_envs_physics.a", "lib/libbsg_algos_training.a"):
        assert (prefix / relative).exists(), relative


def test_installed_bsg_trains_a_run_file_in_an_unrelated_folder(prefix, user_folder):
    run_file = user_folder / "run.yaml"
    run_file.write_text("env_id: SafetyBallCircle-v0\nalg: lag-trpo\nseed: 1\n"
                        "epochs: 2\nsteps_per_epoch: 500\neval_episodes: 1\n")
    bsg = str(prefix / "bin" / "bsg")
    printed = run([bsg, "train", "run.yaml", "--print-config"], cwd=user_folder)
    installed_configs = prefix / "share" / "bsg" / "configs"
    assert printed.splitlines()[0] == f"# configs: {installed_configs} (the installed configs)"
    assert "steps_per_epoch: 500" in printed
    assert "lam: 0.95" in printed  # from the installed algorithms/lag-trpo.yaml

    output = run([bsg, "train", "run.yaml", "--out", "run"], cwd=user_folder)
    assert "epoch    2/2" in output, output
    progress = (user_folder / "run" / "progress.csv").read_text().splitlines()
    assert len(progress) == 3  # header and two epochs
    evaluation = json.loads((user_folder / "run" / "evaluation.json").read_text())
    assert evaluation["episodes"] == 1
    assert evaluation["mean_length"] == 250  # BallCircle's episode length (report Table 3)


def test_installed_bsg_lists_the_environments(prefix, user_folder):
    listed = json.loads(run([str(prefix / "bin" / "bsg"), "envs", "--json"], cwd=user_folder))
    by_id = {entry["id"]: entry for entry in listed}
    assert len([name for name in by_id if name.endswith("-v0")]) == 16  # and the 16 fork variants
    assert len(by_id) == 32
    assert by_id["SafetyAntRun-v0"]["observation_dim"] == 33  # report Table 3
    assert by_id["SafetyAntRun-v0"]["action_dim"] == 8


def in_tree_output():
    assert IN_TREE_STEP_ANT_RUN, "BSG_IN_TREE_STEP_ANT_RUN is not set (run this through ctest)"
    return run([IN_TREE_STEP_ANT_RUN])


def check_same_as_in_tree(output):
    lines = output.splitlines()
    assert lines[0].startswith("reset_observation ") and len(lines[0].split()) == 1 + 33
    assert "steps 100" in lines
    assert output == in_tree_output()


def test_cmake_package_consumer_steps_ant_run_like_the_in_tree_library(prefix, scratch):
    build = scratch / "consumer_build"
    configure = ["cmake", "-S", str(CONSUMER_SOURCE), "-B", str(build), f"-DCMAKE_PREFIX_PATH={prefix}",
                 "-DCMAKE_BUILD_TYPE=Release"]
    if SANITIZE:
        configure += [f"-DCMAKE_CXX_FLAGS={SANITIZER_FLAGS}", f"-DCMAKE_EXE_LINKER_FLAGS={SANITIZER_FLAGS}"]
    run(configure)
    run(["cmake", "--build", str(build)])
    check_same_as_in_tree(run([str(build / "step_ant_run")], cwd=scratch))


def test_pkg_config_consumer_steps_ant_run_like_the_in_tree_library(prefix, scratch):
    environment = user_environment()
    environment["PKG_CONFIG_PATH"] = str(prefix / "lib" / "pkgconfig")
    flags = run(["pkg-config", "--cflags", "--libs", "bsg"], env=environment).split()
    include_dirs = [os.path.realpath(f[2:]) for f in flags if f.startswith("-I")]
    assert os.path.realpath(prefix / "include" / "bsg") in include_dirs, flags
    assert "-lbsg_envs" in flags, flags
    program = scratch / "step_ant_run_pkg_config"
    extra = [SANITIZER_FLAGS] if SANITIZE else []
    run(["g++", "-std=c++20", "-O2", *extra, str(CONSUMER_SOURCE / "step_ant_run.cpp"), "-o", str(program),
         *flags])
    check_same_as_in_tree(run([str(program)], cwd=scratch))
