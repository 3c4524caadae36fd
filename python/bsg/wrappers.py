"""gymnasium's 5-tuple API over a bsg environment.

Libraries written for gymnasium expect ``step`` to return ``(obs, reward,
terminated, truncated, info)``; Safety-Gymnasium-style code reads the cost from
``info["cost"]``. ``GymnasiumEnv(bsg.make(id))`` (or ``bsg.make(id,
api="gymnasium")``) gives that view. When gymnasium is importable the wrapper is
a ``gymnasium.Env``.
"""

from . import spaces as _spaces

_Base = _spaces._gymnasium.Env if _spaces._gymnasium is not None else object


class GymnasiumEnv(_Base):
    """A bsg Env behind gymnasium's API; the cost is in ``info["cost"]``."""

    def __init__(self, env):
        self.env = env
        self.metadata = env.metadata
        self.render_mode = env.render_mode
        self.observation_space = env.observation_space
        self.action_space = env.action_space
        self.spec = env.spec

    def reset(self, *, seed=None, options=None):
        return self.env.reset(seed=seed, options=options)

    def step(self, action):
        obs, reward, cost, terminated, truncated, info = self.env.step(action)
        info["cost"] = cost
        return obs, reward, terminated, truncated, info

    def render(self):
        return self.env.render()

    def close(self):
        self.env.close()

    @property
    def unwrapped(self):
        return self.env

    def __repr__(self):
        return f"GymnasiumEnv({self.env!r})"
