"""The bsg package's Python files import one way only (docs/python.md#the-package):
each imports only files below it in ORDER, at module level and inside
functions alike, so no import depends on another having finished. Oracle: the
import statements themselves, read with Python's own parser."""

import ast
import pathlib

PACKAGE = pathlib.Path(__file__).resolve().parents[2] / "python" / "bsg"
DOCS = pathlib.Path(__file__).resolve().parents[2] / "docs" / "python.md"
# Bottom to top; _core is the C++ module below them all.
ORDER = ["datasets", "gymnasium_support", "spaces", "training", "policies", "rendering", "parallel", "parallel_vector", "env", "specs", "gymnasium_env", "wrappers",
         "vector", "making", "registration", "__init__"]


def package_imports(path):
    """The package's modules that ``path`` imports, anywhere in the file."""
    names = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.ImportFrom) and node.level == 1:
            if node.module:  # from .env import Env
                names.add(node.module.split(".")[0])
            else:  # from . import rendering
                names.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom) and (node.module or "").split(".")[0] == "bsg":
            names.add((node.module.split(".") + ["__init__"])[1])
        elif isinstance(node, ast.Import):
            names.update(a.name.split(".")[1] for a in node.names if a.name.startswith("bsg."))
    return names - {"_core"}


def test_every_file_is_in_the_order():
    assert sorted(p.stem for p in PACKAGE.glob("*.py")) == sorted(ORDER)


def test_each_file_imports_only_files_below_it():
    for path in PACKAGE.glob("*.py"):
        below = set(ORDER[:ORDER.index(path.stem)])
        upward = package_imports(path) - below
        assert not upward, f"{path.name} imports {sorted(upward)}, which are not below it"


def test_docs_state_the_same_order():
    text = " ".join(DOCS.read_text().split())
    assert " → ".join(reversed(ORDER)) in text
