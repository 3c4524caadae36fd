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

import warnings

try:
    import gymnasium
except ImportError:  # gymnasium is optional
    gymnasium = None

OLDEST = (0, 28)


def _release(version):
    """(major, minor) of a version string such as "0.29.1" or "1.4.0"."""
    parts = []
    for part in version.split(".")[:2]:
        digits = "".join(c for c in part if c.isdigit())
        parts.append(int(digits) if digits else 0)
    return tuple(parts + [0] * (2 - len(parts)))


VERSION = getattr(gymnasium, "__version__", None)
if gymnasium is not None and _release(VERSION) < OLDEST:
    warnings.warn(f"bsg supports Gymnasium 0.28, 0.29 and 1.x; the importable Gymnasium is "
                  f"{VERSION}, so bsg does not register its ids with it", UserWarning)
    gymnasium = None  # too old to register with (no vector_entry_point, no EnvSpec fields)
IS_1X = gymnasium is not None and _release(VERSION) >= (1, 0)
