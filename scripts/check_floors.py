#!/usr/bin/env python3
"""The floors of the building (docs/architecture.md#rooms-and-floors): every
project include in the library folders and in the two programs (cli/, the
`bsg` program; python/src/, the Python module) must point at the including
room itself or at a room below it, and from above envs/ only at its face.
Run by every build (CMake target bsg_floors) and by ctest (build.floors,
which also checks that the check fails on an upward include).

Usage: check_floors.py SOURCE_DIR
Exit 0 when every include keeps to its floor; 1, listing every include that
does not ("file:line: room X includes Y, which is above it"), otherwise.
"""
import os
import re
import sys

# Room -> the rooms (or single files) it may include besides itself. A room
# is a folder holding a library or a program; the deepest listed folder that
# contains a file is its room. "envs" is the environments' face, the files
# directly in envs/ (env.h, vector_env, env_benchmark, standard_envs); from
# above envs/, only algos/ also sees envs/description (the value types of
# env.h). algos/ has no face of its own: above it, its top room (training;
# and offline's data files for the program) is seen. docs/architecture.md#rooms-and-floors
# shows this table; tests/docs/test_room_map.py holds the two equal.
ENVS_BELOW_FACE = ["envs/description", "envs/physics", "envs/agents", "envs/sensors", "envs/tasks",
                   "envs/assembly"]
FLOORS = {
    "common": [],
    "envs/description": ["common"],
    "envs/physics": ["envs/description", "common"],
    "envs/agents": ["envs/physics", "envs/description", "common"],
    "envs/sensors": ["envs/agents", "envs/physics", "envs/description", "common"],
    "envs/tasks": ["envs/sensors", "envs/agents", "envs/physics", "envs/description", "common"],
    # The assembly implements the face's Env and MultiAgentEnv interfaces (envs/env.h,
    # envs/multi_agent_env.h): the headers it reads from the floor above, as a game implements spiel.h.
    "envs/assembly": ["envs/tasks", "envs/sensors", "envs/agents", "envs/physics", "envs/description", "common",
                      "envs/env.h", "envs/multi_agent_env.h"],
    "envs": ENVS_BELOW_FACE + ["common"],
    "algos/core": ["envs", "envs/description", "common"],
    "algos/lagrange": ["algos/core", "envs", "envs/description", "common"],
    "algos/trust_region": ["algos/lagrange", "algos/core", "envs", "envs/description", "common"],
    "algos/first_order": ["algos/lagrange", "algos/core", "envs", "envs/description", "common"],
    # Replay buffer, critics and the off-policy updates (SAC, TD3, DDPG and their -lag forms).
    "algos/off_policy": ["algos/lagrange", "algos/core", "envs", "envs/description", "common"],
    # Offline data (DSRL's datasets) and the offline algorithms (behaviour cloning): a family room
    # beside the others, below the training room that runs it.
    "algos/offline": ["algos/lagrange", "algos/core", "envs", "envs/description", "common"],
    # The multi-agent learners' per-agent updates (HAPPO, MACPO): each agent's step is CPO's or PPO's.
    "algos/multi_agent": ["algos/trust_region", "algos/first_order", "algos/lagrange", "algos/core", "envs",
                          "envs/description", "common"],
    "algos/training": ["algos/multi_agent", "algos/offline", "algos/off_policy", "algos/first_order",
                       "algos/trust_region", "algos/lagrange", "algos/core", "envs", "envs/description", "common"],
    # Beside algos: reads a world and a task's markings and draws them.
    "render": ["envs", "envs/assembly", "envs/tasks", "envs/physics", "envs/description", "common"],
    # The numerics of results with their uncertainty (bootstrap, IQM, profiles):
    # numbers in, numbers out, nothing of runs or sweeps.
    "experiments/statistics": ["common"],
    # Only the training room of algos/ is seen from above it.
    "experiments": ["experiments/statistics", "algos/training", "envs", "common"],
    # The `bsg` program: every face, and algos/offline (the dataset files and
    # `bsg dataset`). A collection's constraints are chosen in the training
    # room (algos/training/collection_request.h), not by the program.
    "cli": ["experiments", "algos/offline", "algos/training", "render", "envs", "common"],
    # The Python module binds the environments, the renderer and, of algos/, the training room
    # alone (a run's policy and its evaluation: bsg.load_policy, bsg.evaluate).
    "python/src": ["experiments", "algos/training", "render", "envs", "common"],
}
# A program's own headers are seen by no other room, so its files include
# them by their bare name ("commands.h", beside the including file).
PROGRAM_ROOMS = ("cli", "python/src")
INCLUDE = re.compile(r'^[ \t]*#[ \t]*include\s+"([^"]+)"', re.M)
SOURCE_SUFFIXES = (".h", ".cpp")


def room_of_file(path):
    directory = os.path.dirname(path)
    while directory:
        if directory in FLOORS:
            return directory
        directory = os.path.dirname(directory)
    return None


def allowed(room, included):
    target_room = room_of_file(included)
    if target_room is None or target_room == room:
        return True
    permitted = FLOORS[room]
    return target_room in permitted or included in permitted


def top_folders():
    """The top folders holding rooms: each is walked whole, so a source file
    in a folder of its own (not a room) is reported."""
    return sorted({room.split("/")[0] for room in FLOORS})


def is_beside(source_dir, path, included):
    """A bare name of a file in the including file's own folder."""
    return "/" not in included and os.path.isfile(os.path.join(source_dir, os.path.dirname(path), included))


def check(source_dir):
    problems = []
    for top in top_folders():
        for folder, _, files in os.walk(os.path.join(source_dir, top)):
            for name in sorted(files):
                if not name.endswith(SOURCE_SUFFIXES):
                    continue
                path = os.path.relpath(os.path.join(folder, name), source_dir)
                room = room_of_file(path)
                if room is None:
                    problems.append(f"{path}: in no room (add its folder to FLOORS in scripts/check_floors.py)")
                    continue
                with open(os.path.join(source_dir, path), encoding="utf-8") as source:
                    text = source.read()
                for match in INCLUDE.finditer(text):
                    included = match.group(1)
                    if room in PROGRAM_ROOMS and is_beside(source_dir, path, included):
                        continue
                    if "/" not in included:
                        problems.append(f"{path}:{text.count(chr(10), 0, match.start()) + 1}: include "
                                        f'"{included}" by its full path ("<folder>/{included}")')
                        continue
                    if not allowed(room, included):
                        line = text.count("\n", 0, match.start()) + 1
                        problems.append(f"{path}:{line}: room {room} includes {included}, "
                                        f"which is not on a floor it may include (it may include: {', '.join(FLOORS[room]) or 'nothing'})")
    return problems


def main():
    if len(sys.argv) != 2 or not os.path.isdir(sys.argv[1]):
        print("usage: check_floors.py SOURCE_DIR", file=sys.stderr)
        return 2
    problems = check(sys.argv[1])
    for problem in problems:
        print(problem, file=sys.stderr)
    if problems:
        print(f"check_floors: {len(problems)} include(s) break the floors (docs/architecture.md#rooms-and-floors)",
              file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
