"""Finds Gymnasium for the conformance tests: an installed one first, else the
unmodified source kept beside the repository (the folder `shared/pydeps` next
to the repository's root, or next to the main checkout's root when this is a
git worktree). Without either, the test module is skipped and pytest exits with
code 77 (conftest.py), which ctest reports as skipped (tests/CMakeLists.txt
SKIP_RETURN_CODE): never a pass.

BSG_GYMNASIUM_VERSION ("1", "0.29" or "0.28"; tests/CMakeLists.txt runs the
test_gymnasium*.py files once for each) asks for one version: an installed
gymnasium of that version, else the folder's copy of it (1.4 at the folder's
root, 0.29.1 and 0.28.1 in gymnasium-0.29.1/ and gymnasium-0.28.1/), else
skipped. Unset, any installed version or the folder's 1.4 will do."""

import importlib
import importlib.metadata
import os
import sys
from pathlib import Path

import pytest

SKIP_RETURN_CODE = 77
missing = False  # set when a test module was skipped for want of gymnasium
WANTED = os.environ.get("BSG_GYMNASIUM_VERSION") or None
SUBFOLDERS = {"1": ".", "0.29": "gymnasium-0.29.1", "0.28": "gymnasium-0.28.1"}


def pydeps_folders():
    """Where shared/pydeps may be: beside the repository, or beside the main checkout of a worktree."""
    root = Path(__file__).resolve().parents[2]
    yield root.parent / "shared" / "pydeps"
    git = root / ".git"
    if git.is_file():  # a worktree: "gitdir: <main>/.git/worktrees/<name>"
        gitdir = Path(git.read_text().split("gitdir:", 1)[1].strip())
        yield gitdir.parents[2].parent / "shared" / "pydeps"


def is_wanted(version):
    """Whether ``version`` (e.g. "0.29.1") is the one BSG_GYMNASIUM_VERSION asks for."""
    return WANTED is None or version == WANTED or version.startswith(WANTED + ".")


def _skip(reason):
    global missing
    missing = True
    pytest.skip(reason, allow_module_level=True)


def import_gymnasium():
    """gymnasium (of the version asked for), or skips the calling test module."""
    if WANTED is not None and WANTED not in SUBFOLDERS:
        raise ValueError(f"BSG_GYMNASIUM_VERSION must be one of {sorted(SUBFOLDERS)}, got {WANTED!r}")
    try:
        installed = importlib.metadata.version("gymnasium")
    except importlib.metadata.PackageNotFoundError:
        installed = None
    if installed is not None and is_wanted(installed):
        return importlib.import_module("gymnasium")
    for folder in pydeps_folders():
        source = (folder / SUBFOLDERS[WANTED or "1"]).resolve()
        if (source / "gymnasium" / "__init__.py").is_file():
            # The version's folder first; the root after it for farama_notifications.
            sys.path[0:0] = [str(source), str(folder)]
            gymnasium = importlib.import_module("gymnasium")
            if not is_wanted(gymnasium.__version__):
                raise ImportError(f"{source} holds gymnasium {gymnasium.__version__}, "
                                  f"not {WANTED}")
            return gymnasium
    _skip(f"gymnasium {WANTED or ''} is neither installed nor in shared/pydeps beside the "
          f"repository")


def import_pettingzoo():
    """pettingzoo (with a Gymnasium 1.x it needs), installed first, else the core kept in
    shared/pydeps beside the repository; or skips the calling test module."""
    try:
        return importlib.import_module("pettingzoo")
    except ImportError:
        pass
    for folder in pydeps_folders():
        if (folder / "pettingzoo" / "__init__.py").is_file():
            import_gymnasium()  # an installed 1.x, else the folder's, which PettingZoo needs
            if str(folder) not in sys.path:
                sys.path.insert(0, str(folder))
            return importlib.import_module("pettingzoo")
    _skip("pettingzoo is neither installed nor in shared/pydeps beside the repository")
