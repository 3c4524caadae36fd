"""Gymnasium's single-environment API over a bsg environment.

``GymnasiumEnv(bsg.make(id))`` (or ``bsg.make(id, api="gymnasium")``, or
``gymnasium.make("bsg/<id>")``) steps with gymnasium's 5-tuple ``(obs, reward,
terminated, truncated, info)``; the cost is ``info["cost"]`` beside the task's
cost terms. When gymnasium is importable the class is a ``gymnasium.Env``:
``unwrapped`` is itself, ``reset(seed=s)`` seeds ``np_random``, ``spec`` is
gymnasium's ``EnvSpec`` of the registered id (``bsg_spec`` is bsg's),
``metadata`` names the render modes and frame rate. It pickles and copies like
the bsg environment inside it (docs/python.md#pickle-and-copy).
"""

import warnings

from . import rendering as _rendering
from .gymnasium_support import gymnasium as _gymnasium
from .specs import gymnasium_spec

_Base = _gymnasium.Env if _gymnasium is not None else object


class GymnasiumEnv(_Base):
    """A bsg ``Env`` behind gymnasium's API; the cost is in ``info["cost"]``.

    The action space is ``Box(-1, 1)``. Out-of-range actions are not errors:
    as in the original suite the Ball, the Drone and the Ant clip them to
    [-1, 1] and the Car uses them as given; the first one warns
    (``UserWarning``, once per environment, as gymnasium's passive checker
    does).
    """

    metadata = _rendering.METADATA

    def __init__(self, env):
        self.env = env
        self.observation_space = env.observation_space
        self.action_space = env.action_space
        self.render_mode = getattr(env, "render_mode", None)
        self.spec = _registered_spec(env)

    @property
    def unwrapped(self):
        return self

    @property
    def bsg_spec(self):
        """bsg's ``EnvSpec`` (agent, task, dimensions, episode length, cost limit)."""
        return self.env.spec

    def reset(self, *, seed=None, options=None):
        if _gymnasium is not None:
            super().reset(seed=seed)  # seeds self.np_random
        return self.env.reset(seed=seed, options=options)

    def step(self, action):
        obs, reward, cost, terminated, truncated, info = self.env.step(action)
        info["cost"] = cost
        return obs, reward, terminated, truncated, info

    def render(self):
        if self.render_mode is None:
            warnings.warn("WARN: You are calling render method without specifying any render "
                          "mode; make the environment with render_mode='rgb_array'.",
                          UserWarning, stacklevel=2)
            return None
        return self.env.render()

    def close(self):
        self.env.close()

    def __repr__(self):
        return f"GymnasiumEnv({self.env!r})"


def _registered_spec(env):
    """gymnasium's EnvSpec of the env's id with its options, or bsg's spec without gymnasium."""
    spec = gymnasium_spec(getattr(env, "_env_id", env.spec.id), getattr(env, "_options", {}),
                          getattr(env, "_max_episode_steps", None) or None)
    return env.spec if spec is None else spec
