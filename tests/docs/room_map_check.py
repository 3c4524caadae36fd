"""The map of rooms in docs/architecture.md against the tree (test_room_map.py runs it).

docs/architecture.md#rooms-and-floors has a table with one row per room (its folder, its CMake
target, the rooms it may include) and, under "What each room holds", a heading per room
(#### `room`) with one bullet per file: "- `world`: ..." names world.h and world.cpp (whichever
exist), "- `marking.h`: ..." names that one file. The check holds them to the code:

- the table's rooms are the rooms of scripts/check_floors.py's FLOORS, each an existing folder,
  and what a row may include is that room's FLOORS entry;
- a room's target is its bsg_add_library line in CMakeLists.txt, or, for a program, a target
  made by add_executable or pybind11_add_module;
- every room has its heading, and every .h and .cpp file of a room (the deepest room holding it)
  is named by exactly one bullet of that heading; a bullet names only files that exist.

So a new file needs one line under its room's heading, a new room a table row and a heading.
"""

import glob
import importlib.util
import os
import re

DOC = 'docs/architecture.md'
TABLE_HEADER = re.compile(r'^\|\s*room\s*\|\s*CMake target\s*\|\s*may include')
FILES_SECTION = '### What each room holds'
ROOM_HEADING = re.compile(r'^#### `([^`]+)`')
FILE_BULLET = re.compile(r'^- `([^`]+)`')
TICKED = re.compile(r'`([^`]+)`')
SOURCE_SUFFIXES = ('.h', '.cpp')


def load_floors(source_dir):
    """FLOORS of the tree's own scripts/check_floors.py."""
    path = os.path.join(source_dir, 'scripts', 'check_floors.py')
    spec = importlib.util.spec_from_file_location('check_floors_of_tree', path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module.FLOORS


def room_of(path, floors):
    directory = os.path.dirname(path)
    while directory:
        if directory in floors:
            return directory
        directory = os.path.dirname(directory)
    return None


def files_by_room(source_dir, floors):
    rooms = {room: set() for room in floors}
    for top in sorted({room.split('/')[0] for room in floors}):
        for folder, _, names in os.walk(os.path.join(source_dir, top)):
            for name in names:
                if name.endswith(SOURCE_SUFFIXES):
                    path = os.path.relpath(os.path.join(folder, name), source_dir).replace(os.sep, '/')
                    room = room_of(path, floors)
                    if room is not None:
                        rooms[room].add(path)
    return rooms


def cmake_targets(source_dir):
    """(folder -> bsg_add_library target, set of program targets) of the tree's CMake files."""
    libraries, programs = {}, set()
    lists = [os.path.join(source_dir, 'CMakeLists.txt')] + glob.glob(os.path.join(source_dir, '*', 'CMakeLists.txt'))
    for path in lists:
        if os.path.relpath(path, source_dir).startswith('tests'):
            continue
        with open(path, encoding='utf-8') as f:
            text = f.read()
        for name, folder in re.findall(r'^\s*bsg_add_library\((\w+)\s+([\w/]+)', text, re.M):
            libraries[folder] = name
        programs.update(re.findall(r'^\s*(?:add_executable|pybind11_add_module)\((\w+)', text, re.M))
    return libraries, programs


def parse_table(lines):
    """[(line number, room, target, may include)] of the rooms table."""
    rows = []
    start = next((i for i, line in enumerate(lines) if TABLE_HEADER.match(line)), None)
    if start is None:
        return rows
    for number in range(start + 2, len(lines)):
        line = lines[number]
        if not line.startswith('|'):
            break
        cells = [cell.strip() for cell in line.strip().strip('|').split('|')]
        ticked = [TICKED.findall(cell) for cell in cells]
        if len(cells) < 3 or not ticked[0]:
            rows.append((number + 1, None, None, None))
            continue
        rows.append((number + 1, ticked[0][0], ticked[1][0] if ticked[1] else None, ticked[2]))
    return rows


def parse_file_lists(lines):
    """room -> [(line number, name)] of the bullets under "What each room holds"."""
    lists = {}
    inside = False
    room = None
    for number, line in enumerate(lines, start=1):
        if line.startswith(FILES_SECTION):
            inside = True
            continue
        if not inside:
            continue
        if line.startswith('## ') or line.startswith('### '):
            break
        heading = ROOM_HEADING.match(line)
        if heading:
            room = heading.group(1)
            lists.setdefault(room, [])
            continue
        bullet = FILE_BULLET.match(line)
        if bullet and room is not None:
            lists[room].append((number, bullet.group(1)))
    return lists


def named_files(room, name, files):
    """The files of `room` a bullet's name stands for."""
    if name.endswith(SOURCE_SUFFIXES):
        candidates = [f'{room}/{name}']
    else:
        candidates = [f'{room}/{name}{suffix}' for suffix in SOURCE_SUFFIXES]
    return [path for path in candidates if path in files]


def check(source_dir, floors=None):
    """Every difference between the map in docs/architecture.md and the tree, one line each."""
    floors = load_floors(source_dir) if floors is None else floors
    with open(os.path.join(source_dir, DOC), encoding='utf-8') as f:
        lines = f.read().split('\n')
    problems = []
    libraries, programs = cmake_targets(source_dir)

    rows = parse_table(lines)
    if not rows:
        problems.append(f'{DOC}: no rooms table (a header "| room | CMake target | may include ... |")')
    seen = set()
    for number, room, target, may_include in rows:
        where = f'{DOC}:{number}'
        if room is None:
            problems.append(f'{where}: a row of the rooms table without a `room` in its first cell')
            continue
        if room in seen:
            problems.append(f'{where}: room {room} has a second row')
        seen.add(room)
        if room not in floors:
            problems.append(f'{where}: room {room} is not in FLOORS (scripts/check_floors.py)')
            continue
        expected = libraries.get(room)
        if expected is not None and target != expected:
            problems.append(f'{where}: room {room} is CMake library {expected}, not {target}')
        if expected is None and target not in programs:
            problems.append(f'{where}: room {room} names target {target}, which no bsg_add_library, '
                            'add_executable or pybind11_add_module makes')
        if set(may_include) != set(floors[room]):
            problems.append(f'{where}: room {room} may include {", ".join(sorted(floors[room])) or "nothing"} '
                            f'(FLOORS), the table says {", ".join(sorted(may_include)) or "nothing"}')
    for room in floors:
        if not os.path.isdir(os.path.join(source_dir, room)):
            problems.append(f'scripts/check_floors.py: room {room} is not a folder')
        if room not in seen:
            problems.append(f'{DOC}: room {room} of FLOORS has no row in the rooms table')

    lists = parse_file_lists(lines)
    files = files_by_room(source_dir, floors)
    for room in lists:
        if room not in floors:
            problems.append(f'{DOC}: "#### `{room}`" is not a room of FLOORS')
    for room in floors:
        if room not in lists:
            problems.append(f'{DOC}: room {room} has no "#### `{room}`" list of its files under "{FILES_SECTION}"')
            continue
        covered = {}
        for number, name in lists[room]:
            named = named_files(room, name, files[room])
            if not named:
                problems.append(f'{DOC}:{number}: `{name}` is not a file of room {room}')
            for path in named:
                if path in covered:
                    problems.append(f'{DOC}:{number}: {path} is named twice (also line {covered[path]})')
                covered[path] = number
        for path in sorted(files[room] - covered.keys()):
            stem = os.path.splitext(os.path.basename(path))[0]
            problems.append(f'{DOC}: {path} is not named under "#### `{room}`" (add a line "- `{stem}`: what it is")')
    return problems


def main(argv):
    source_dir = argv[1] if len(argv) > 1 else os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..')
    problems = check(source_dir)
    for problem in problems:
        print(problem)
    return 1 if problems else 0


if __name__ == '__main__':
    import sys
    sys.exit(main(sys.argv))
