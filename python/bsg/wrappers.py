"""Wrappers over a bsg environment, for either API.

``GymnasiumEnv`` (gymnasium_env.py) gives gymnasium's 5-tuple;
``NextStepAutoreset`` resets an ended episode in the next step, as gymnasium
1.x's Autoreset wrapper does, for the 6-tuple and the 5-tuple alike
(``bsg.make(id, autoreset=True)``).
"""

from .gymnasium_env import GymnasiumEnv

__all__ = ["GymnasiumEnv", "NextStepAutoreset"]


class NextStepAutoreset:
    """After a step that ends the episode, the next ``step`` resets instead:
    it returns the new episode's first observation, reward 0 (and cost 0),
    ``terminated = truncated = False`` and the reset's info."""

    def __init__(self, env):
        self.env = env
        self._ended = False

    def __getattr__(self, name):
        if name == "env":  # not yet set (unpickling)
            raise AttributeError(name)
        return getattr(self.env, name)

    def reset(self, *, seed=None, options=None):
        self._ended = False
        return self.env.reset(seed=seed, options=options)

    def step(self, action):
        if self._ended:
            obs, info = self.env.reset()
            self._ended = False
            return (obs, 0.0, False, False, info) if isinstance(self.env, GymnasiumEnv) \
                else (obs, 0.0, 0.0, False, False, info)
        result = self.env.step(action)
        self._ended = bool(result[-3] or result[-2])
        return result

    def __repr__(self):
        return f"NextStepAutoreset({self.env!r})"
