"""Which Gymnasium bsg works with, found once at import.

bsg supports Gymnasium 0.28, 0.29 and 1.x (docs/python.md#gymnasium-versions).
``gymnasium`` is the imported module, or None when Gymnasium is missing or older
than 0.28 (then bsg behaves as without it: NumPy spaces, no registration).
``IS_1X`` tells the two generations apart where their APIs differ: 1.x's vector
environments reset in the next step by default (``AutoresetMode``) and report
``final_obs``; 0.28 and 0.29 reset in the same step and report
``final_observation``.

This module is the bottom of the package's Python files: it imports nothing of
bsg, and every other file may import it.
"""

import importlib
import importlib.metadata
import re
import warnings

try:
    import gymnasium
except ImportError:  # gymnasium is optional
    gymnasium = None

OLDEST = (0, 28)
# What bsg uses of Gymnasium beyond its top level.
_SUBMODULES = ("envs.registration", "spaces", "vector", "wrappers", "utils.seeding")


def _version(module):
    """The version of the imported Gymnasium ``module``.

    Gymnasium 0.x loads its plugins (bsg's entry point, docs/python.md#registration) half way
    through its own import, before it sets ``__version__``: then the installed distribution's
    version, else the one its ``__init__.py`` sets.
    """
    version = getattr(module, "__version__", None)
    if version is not None:
        return version
    try:
        return importlib.metadata.version("gymnasium")
    except importlib.metadata.PackageNotFoundError:
        with open(module.__file__, encoding="utf-8") as source:
            found = re.search(r"""^__version__\s*=\s*["']([^"']+)["']""", source.read(), re.M)
        return found.group(1) if found else "0"


def _release(version):
    """(major, minor) of a version string such as "0.29.1" or "1.4.0"."""
    parts = []
    for part in version.split(".")[:2]:
        digits = "".join(c for c in part if c.isdigit())
        parts.append(int(digits) if digits else 0)
    return tuple(parts + [0] * (2 - len(parts)))


VERSION = _version(gymnasium) if gymnasium is not None else None
if gymnasium is not None and _release(VERSION) < OLDEST:
    warnings.warn(f"bsg supports Gymnasium 0.28, 0.29 and 1.x; the importable Gymnasium is "
                  f"{VERSION}, so bsg does not register its ids with it", UserWarning)
    gymnasium = None  # too old to register with (no vector_entry_point, no EnvSpec fields)
IS_1X = gymnasium is not None and _release(VERSION) >= (1, 0)
# Half way through Gymnasium's import (a plugin being loaded) its subpackages are not bound yet:
# imported here, they are; ``registration`` is the module registering goes through, bound or not.
registration = None
if gymnasium is not None:
    for _name in _SUBMODULES:
        importlib.import_module(f"gymnasium.{_name}")
    registration = importlib.import_module("gymnasium.envs.registration")
