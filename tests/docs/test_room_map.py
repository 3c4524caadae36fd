"""The map of rooms (room_map_check.py): docs/architecture.md names every room of
scripts/check_floors.py with its target and floors and every file of every room; on small
hand-made trees, each kind of drift is reported with the line to fix."""

import os
import sys

import pytest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import room_map_check  # noqa: E402

SOURCE_DIR = os.environ.get(
    'BSG_SOURCE_DIR', os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..'))

FLOORS = {'core': [], 'core/maths': ['core'], 'tool': ['core/maths', 'core']}
TABLE = ('| room | CMake target | may include (besides itself) |\n|---|---|---|\n'
         '| `core` | `lib_core` | nothing |\n'
         '| `core/maths` | `lib_maths` | `core` |\n'
         '| `tool` | `tool` | `core/maths`, `core` |\n')
LISTS = ('### What each room holds\n\n'
         '#### `core`\n\n- `text`: strings.\n- `units.h`: units.\n\n'
         '#### `core/maths`\n\n- `solve`: a solver,\n  over two lines.\n\n'
         '#### `tool`\n\n- `main.cpp`: the program.\n\n'
         '## Next section\n\n- `not_a_file`: prose after the lists.\n')


def write(root, relative, text=''):
    path = os.path.join(root, relative)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, 'w', encoding='utf-8') as f:
        f.write(text)


@pytest.fixture
def tree(tmp_path):
    write(tmp_path, 'CMakeLists.txt', 'bsg_add_library(lib_core core)\nbsg_add_library(lib_maths core/maths lib_core)\n'
                                      'add_executable(tool ${tool_sources})\n')
    for path in ('core/text.h', 'core/text.cpp', 'core/units.h', 'core/maths/solve.h', 'core/maths/solve.cpp',
                 'tool/main.cpp', 'core/notes.txt'):
        write(tmp_path, path)
    write(tmp_path, 'docs/architecture.md', '# Architecture\n\n' + TABLE + '\n' + LISTS)
    return tmp_path


def problems_of(root):
    return room_map_check.check(str(root), FLOORS)


def edit_doc(root, old, new):
    path = os.path.join(root, 'docs', 'architecture.md')
    with open(path, encoding='utf-8') as f:
        text = f.read()
    assert old in text
    write(root, 'docs/architecture.md', text.replace(old, new))


def test_the_repository_map_is_true_to_the_code():
    problems = room_map_check.check(SOURCE_DIR)
    assert problems == [], '\n'.join(problems)


def test_a_true_map_passes(tree):
    assert problems_of(tree) == []


def test_a_new_file_must_be_named_under_its_room(tree):
    write(tree, 'core/maths/matrix.h')
    assert problems_of(tree) == [
        'docs/architecture.md: core/maths/matrix.h is not named under "#### `core/maths`" '
        '(add a line "- `matrix`: what it is")']


def test_a_named_file_that_is_gone_or_in_another_room_fails(tree):
    os.remove(os.path.join(tree, 'core', 'units.h'))
    edit_doc(tree, '- `main.cpp`: the program.', '- `main.cpp`: the program.\n- `solve`: not here.')
    assert problems_of(tree) == [
        'docs/architecture.md:14: `units.h` is not a file of room core',
        'docs/architecture.md:24: `solve` is not a file of room tool']


def test_a_file_named_twice_fails(tree):
    edit_doc(tree, '- `text`: strings.', '- `text`: strings.\n- `text.h`: again.')
    assert problems_of(tree) == [
        'docs/architecture.md:14: core/text.h is named twice (also line 13)']


def test_a_room_without_row_heading_or_folder_fails(tree):
    floors = dict(FLOORS, plugin=['core'])
    assert room_map_check.check(str(tree), floors) == [
        'scripts/check_floors.py: room plugin is not a folder',
        'docs/architecture.md: room plugin of FLOORS has no row in the rooms table',
        'docs/architecture.md: room plugin has no "#### `plugin`" list of its files under "### What each room holds"']


def test_a_row_must_say_the_floors_and_the_target_of_the_code(tree):
    edit_doc(tree, '| `core/maths` | `lib_maths` | `core` |', '| `core/maths` | `lib_math` | nothing |')
    edit_doc(tree, '| `tool` | `tool` |', '| `tool` | `the_tool` |')
    assert problems_of(tree) == [
        'docs/architecture.md:6: room core/maths is CMake library lib_maths, not lib_math',
        'docs/architecture.md:6: room core/maths may include core (FLOORS), the table says nothing',
        'docs/architecture.md:7: room tool names target the_tool, which no bsg_add_library, add_executable '
        'or pybind11_add_module makes']


def test_a_row_or_heading_of_no_room_fails(tree):
    edit_doc(tree, '| `tool` | `tool` | `core/maths`, `core` |\n',
             '| `tool` | `tool` | `core/maths`, `core` |\n| `old` | `lib_old` | nothing |\n')
    edit_doc(tree, '## Next section', '#### `old`\n\n## Next section')
    assert problems_of(tree) == [
        'docs/architecture.md:8: room old is not in FLOORS (scripts/check_floors.py)',
        'docs/architecture.md: "#### `old`" is not a room of FLOORS']
