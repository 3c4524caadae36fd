"""Observation and action spaces.

``box(low, high, shape)`` returns a real ``gymnasium.spaces.Box`` when
gymnasium can be imported, so that libraries checking ``isinstance(space,
gymnasium.spaces.Box)`` accept bsg's environments; otherwise a ``Box`` of this
module with the same attributes and the methods RL code uses (``sample``,
``contains``, ``seed``).

Action spaces are ``box(-1, 1, (action_dim,))``. An action outside them is not
an error: as in the original suite, the Ball, the Drone and the Ant clip it to
[-1, 1] and the Car uses it as given (docs/environments.md#kept-quirks, quirk 4);
each environment warns about the first one (``UserWarning``, once, the
convention of gymnasium's passive environment checker). NaN and infinite
entries raise ValueError.
"""

import numpy as np

from .gymnasium_support import gymnasium as _gymnasium


class Box:
    """A box in R^n: ``low <= x <= high`` elementwise, float64 (gymnasium's Box API)."""

    def __init__(self, low, high, shape, dtype=np.float64, seed=None):
        self.shape = tuple(int(n) for n in shape)
        self.dtype = np.dtype(dtype)
        self.low = np.full(self.shape, low, dtype=self.dtype)
        self.high = np.full(self.shape, high, dtype=self.dtype)
        self._np_random = np.random.default_rng(seed)

    def seed(self, seed=None):
        self._np_random = np.random.default_rng(seed)
        return [seed]

    @property
    def np_random(self):
        return self._np_random

    def sample(self):
        """A uniform draw from the box."""
        return self._np_random.uniform(self.low, self.high).astype(self.dtype)

    def contains(self, x):
        x = np.asarray(x)
        return bool(
            x.shape == self.shape
            and np.can_cast(x.dtype, self.dtype)
            and np.all(x >= self.low)
            and np.all(x <= self.high)
        )

    def __contains__(self, x):
        return self.contains(x)

    def __eq__(self, other):
        return (
            isinstance(other, Box)
            and self.shape == other.shape
            and self.dtype == other.dtype
            and np.array_equal(self.low, other.low)
            and np.array_equal(self.high, other.high)
        )

    def __repr__(self):
        return f"Box({self.low.flat[0]}, {self.high.flat[0]}, {self.shape}, {self.dtype})"


def box(low, high, shape):
    """A float64 box, gymnasium's when gymnasium is importable."""
    if _gymnasium is not None:
        return _gymnasium.spaces.Box(low=low, high=high, shape=tuple(shape), dtype=np.float64)
    return Box(low, high, shape)
