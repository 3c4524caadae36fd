"""scripts/check_floors.py: the real tree keeps its floors; an include that
runs upward, one from a program (cli/, python/src/) below the environments'
face, an include without its folder and a file in no room are each refused
with the file, the line and what the room may include."""
import os
import pathlib
import subprocess
import sys

SOURCE_DIR = pathlib.Path(__file__).resolve().parents[2]
SCRIPT = SOURCE_DIR / "scripts" / "check_floors.py"


def run(tree):
    return subprocess.run([sys.executable, str(SCRIPT), str(tree)], capture_output=True, text=True)


def write(root, path, text):
    target = root / path
    target.parent.mkdir(parents=True, exist_ok=True)
    target.write_text(text)


def test_the_repository_keeps_its_floors():
    result = run(SOURCE_DIR)
    assert result.returncode == 0, result.stderr


def test_an_upward_include_is_refused_with_file_line_and_the_rooms_allowed(tmp_path):
    write(tmp_path, "envs/physics/world.h", '#pragma once\n#include "common/random.h"\n')
    write(tmp_path, "envs/physics/ray_fan.cpp", '#include "envs/physics/world.h"\n\n#include "envs/agents/agent.h"\n')
    write(tmp_path, "envs/agents/agent.h", '#pragma once\n#include "envs/physics/world.h"\n')
    write(tmp_path, "algos/core/buffer.cpp", '#include "algos/training/trainer.h"\n')
    result = run(tmp_path)
    assert result.returncode == 1
    assert ("envs/physics/ray_fan.cpp:3: room envs/physics includes envs/agents/agent.h, which is not on a floor it may "
            "include (it may include: envs/description, common)") in result.stderr
    assert "algos/core/buffer.cpp:1: room algos/core includes algos/training/trainer.h" in result.stderr
    assert "2 include(s) break the floors" in result.stderr  # the downward includes pass


def test_a_bare_include_and_a_file_in_no_room_are_refused(tmp_path):
    write(tmp_path, "render/camera.cpp", '#include "camera.h"\n')
    write(tmp_path, "algos/model_based/dyna.cpp", '#include "algos/core/algorithm.h"\n')
    result = run(tmp_path)
    assert result.returncode == 1
    assert 'render/camera.cpp:1: include "camera.h" by its full path' in result.stderr
    assert "algos/model_based/dyna.cpp: in no room (add its folder to FLOORS in scripts/check_floors.py)" in result.stderr


def test_the_face_may_be_included_by_the_assembly_only(tmp_path):
    write(tmp_path, "envs/assembly/assembled_env.h", '#pragma once\n#include "envs/env.h"\n')
    write(tmp_path, "envs/tasks/task.h", '#pragma once\n#include "envs/env.h"\n')
    result = run(tmp_path)
    assert result.returncode == 1
    assert "envs/tasks/task.h:2: room envs/tasks includes envs/env.h" in result.stderr
    assert "assembled_env.h" not in result.stderr


def test_the_program_includes_faces_only(tmp_path):
    write(tmp_path, "cli/commands.h", '#pragma once\n#include "envs/env.h"\n')
    write(tmp_path, "cli/cmd_envs.cpp", '#include "commands.h"\n#include "envs/standard_envs.h"\n'
                                         '#include "envs/description/standard_descriptions.h"\n')
    write(tmp_path, "cli/cmd_collect.cpp", '#include "algos/offline/collection.h"\n'
                                            '#include "algos/core/constraint_costs.h"\n#include "algos/core/buffer.h"\n')
    write(tmp_path, "cli/cmd_bench.cpp", '#include "envs/physics/world.h"\n#include "missing.h"\n')
    result = run(tmp_path)
    assert result.returncode == 1
    assert ("cli/cmd_envs.cpp:3: room cli includes envs/description/standard_descriptions.h, which is not on a "
            "floor it may include") in result.stderr
    assert "cli/cmd_collect.cpp:1:" not in result.stderr  # algos/offline is a top room of algos/
    assert "cli/cmd_collect.cpp:2: room cli includes algos/core/constraint_costs.h" in result.stderr
    assert "cli/cmd_collect.cpp:3: room cli includes algos/core/buffer.h" in result.stderr
    assert "cli/cmd_bench.cpp:1: room cli includes envs/physics/world.h" in result.stderr
    assert 'cli/cmd_bench.cpp:2: include "missing.h" by its full path' in result.stderr
    assert "5 include(s) break the floors" in result.stderr  # the faces and a header beside only


def test_a_library_may_not_include_the_program_nor_the_python_module(tmp_path):
    write(tmp_path, "cli/recording.h", '#pragma once\n')
    write(tmp_path, "python/src/arguments.h", '#pragma once\n#include "render/camera.h"\n#include "algos/off_policy/replay_buffer.h"\n')
    write(tmp_path, "experiments/sweep_plan.cpp", '#include "cli/recording.h"\n')
    write(tmp_path, "python/src/extra/binding.cpp", '#include "envs/env.h"\n')
    write(tmp_path, "python/src/module.cpp", '#include "arguments.h"\n#include "envs/physics/world.h"\n')
    result = run(tmp_path)
    assert result.returncode == 1
    assert "experiments/sweep_plan.cpp:1: room experiments includes cli/recording.h" in result.stderr
    assert "python/src/arguments.h:3: room python/src includes algos/off_policy/replay_buffer.h" in result.stderr
    assert "python/src/module.cpp:2: room python/src includes envs/physics/world.h" in result.stderr
    assert "python/src/extra/binding.cpp" not in result.stderr  # the deepest room holding it is python/src
    assert "3 include(s) break the floors" in result.stderr
