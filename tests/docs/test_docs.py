"""The documentation check (docs_check.py): the repository passes it, and it catches each kind
of problem on small hand-made trees whose answer is known."""

import os
import sys

import pytest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import docs_check  # noqa: E402

SOURCE_DIR = os.environ.get(
    'BSG_SOURCE_DIR', os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..'))

# Built from pieces so that this file itself passes the check.
SHARED = '../' + 'shared'
SECTION = 'spec ' + '\u00a7'
GUIDE = 'docs/' + 'guide.md'  # a pointer spelled out here would be checked against this repository


def write(root, relative, text):
    path = os.path.join(root, relative)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, 'w', encoding='utf-8') as f:
        f.write(text)


def problems_of(root):
    return docs_check.Checker(str(root)).run()


@pytest.fixture
def tree(tmp_path):
    write(tmp_path, 'docs/guide.md',
          '# Guide\n\n## Ball and Car\n\n### The `obs_clip` key (Q3)\n\n'
          '```\n## not a heading\n```\n\n## Ball and Car\n')
    write(tmp_path, 'README.md', f'See [the guide]({GUIDE}#ball-and-car).\n')
    write(tmp_path, 'src/a.cpp', f'// see {GUIDE}#ball-and-car, #the-obs_clip-key-q3\n')
    return tmp_path


def test_the_repository_documentation_is_self_contained():
    problems = problems_of(SOURCE_DIR)
    assert problems == [], '\n'.join(problems)


def test_the_repository_has_the_four_documents():
    for name in ('environments', 'algorithms', 'reproducing', 'architecture'):
        assert os.path.isfile(os.path.join(SOURCE_DIR, 'docs', name + '.md')), name


def test_github_slugs_of_hand_written_headings():
    assert docs_check.github_slug('Ball and Car') == 'ball-and-car'
    assert docs_check.github_slug('The `obs_clip` key (Q3)') == 'the-obs_clip-key-q3'
    assert docs_check.github_slug('TRPO-L: Lagrangian TRPO') == 'trpo-l-lagrangian-trpo'
    assert docs_check.github_slug("The report's protocol") == 'the-reports-protocol'
    assert docs_check.github_slug('Pseudo-LIDAR [link](x.md)') == 'pseudo-lidar-link'


def test_duplicate_headings_get_numbered_anchors_and_fenced_lines_are_not_headings():
    anchors = docs_check.anchors_of('## A\n```\n## B\n```\n## A\n')
    assert anchors == {'a', 'a-1'}


def test_a_clean_tree_passes(tree):
    assert problems_of(tree) == []


def test_a_link_to_a_missing_file_fails(tree):
    write(tree, 'configs/README.md', 'Keys: [guide](../docs/missing.md).\n')
    assert problems_of(tree) == ['configs/README.md:1: link ../docs/missing.md: no such file']


def test_a_link_to_a_missing_anchor_fails(tree):
    write(tree, 'README.md', f'See [the guide]({GUIDE}#ball-and-drone).\n')
    assert problems_of(tree) == [
        f'README.md:1: link {GUIDE}#ball-and-drone: no heading with anchor #ball-and-drone']


def test_a_link_to_a_heading_inside_a_code_fence_fails(tree):
    write(tree, 'README.md', f'[x]({GUIDE}#not-a-heading)\n')
    assert problems_of(tree) == [
        f'README.md:1: link {GUIDE}#not-a-heading: no heading with anchor #not-a-heading']


def test_links_inside_code_are_not_links(tree):
    write(tree, 'README.md', 'Write `[x](nowhere.md)` or\n```\n[y](nowhere.md)\n```\n')
    assert problems_of(tree) == []


def test_a_code_comment_pointing_at_a_missing_anchor_fails(tree):
    write(tree, 'src/b.h', f'// {GUIDE}#ball-and-car, #drone\n')
    assert problems_of(tree) == [f'src/b.h:1: {GUIDE}#drone: no heading with anchor #drone']


def test_a_code_comment_pointing_at_a_missing_document_fails(tree):
    write(tree, 'src/b.h', '# docs/' + 'nothing.md#ball-and-car\n')
    assert problems_of(tree) == ['src/b.h:1: docs/' + 'nothing.md#ball-and-car: no such file']


def test_a_reference_outside_the_repository_fails_anywhere(tree):
    write(tree, 'docs/other.md', f'Taken from `{SHARED}/spec/x.md`.\n')
    problems = problems_of(tree)
    assert len(problems) == 2  # one for each forbidden spelling the line contains
    assert all(p.startswith('docs/other.md:1: refers outside the repository') for p in problems)


def test_a_spec_section_citation_fails_outside_docs_only(tree):
    write(tree, 'src/c.cpp', f'// the reset ({SECTION}2.6)\n')
    write(tree, 'docs/notes.md', f'The original cited {SECTION}2.6.\n')
    assert problems_of(tree) == [
        'src/c.cpp:1: cites an external specification; point at docs/']


def test_the_command_line_exits_non_zero_on_a_problem(tree, capsys):
    assert docs_check.main(['docs_check.py', str(tree)]) == 0
    write(tree, 'README.md', '[gone](docs/gone.md)\n')
    assert docs_check.main(['docs_check.py', str(tree)]) == 1
    assert 'README.md:1: link docs/gone.md: no such file' in capsys.readouterr().out
