"""Finds Gymnasium for the conformance tests: an installed one first, else the
unmodified source kept beside the repository (the folder `shared/pydeps` next
to the repository's root, or next to the main checkout's root when this is a
git worktree). Without either, the test module is skipped and pytest exits with
code 77 (conftest.py), which ctest reports as skipped (tests/CMakeLists.txt
SKIP_RETURN_CODE): never a pass."""

import importlib
import sys
from pathlib import Path

import pytest

SKIP_RETURN_CODE = 77
missing = False  # set when a test module was skipped for want of gymnasium


def _candidate_folders():
    root = Path(__file__).resolve().parents[2]
    yield root.parent / "shared" / "pydeps"
    git = root / ".git"
    if git.is_file():  # a worktree: "gitdir: <main>/.git/worktrees/<name>"
        gitdir = Path(git.read_text().split("gitdir:", 1)[1].strip())
        yield gitdir.parents[2].parent / "shared" / "pydeps"


def import_gymnasium():
    """gymnasium, or skips the calling test module."""
    global missing
    try:
        return importlib.import_module("gymnasium")
    except ImportError:
        pass
    for folder in _candidate_folders():
        if (folder / "gymnasium" / "__init__.py").is_file():
            sys.path.insert(0, str(folder))
            return importlib.import_module("gymnasium")
    missing = True
    pytest.skip("gymnasium is neither installed nor in shared/pydeps beside the repository",
                allow_module_level=True)
