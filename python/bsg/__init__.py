"""bsg: the 16 Bullet-Safety-Gym environments from C++, for Python.

    import bsg
    env = bsg.make("SafetyBallCircle-v0")
    obs, info = env.reset(seed=0)
    obs, reward, cost, terminated, truncated, info = env.step(env.action_space.sample())

``bsg.env_ids()`` lists the ids; ``bsg.VectorEnv(id, num_envs)`` steps many
environments on a C++ thread pool; ``bsg.make(id, api="gymnasium")`` gives
gymnasium's 5-tuple with the cost in ``info["cost"]``.

Every other keyword argument changes a parameter of the environment's
description (``bsg.describe(id)`` lists them, docs/environments.md):
``bsg.make("SafetyBallGather-v0", bombs=12)``, or a new combination
``bsg.make(agent="Drone", task="Reach", zones=4)``; the same for
``bsg.VectorEnv``. A bad key or value raises ValueError naming it.
"""

from . import _core
from .spaces import Box, box
from .wrappers import GymnasiumEnv

__all__ = ["make", "describe", "env_ids", "Env", "VectorEnv", "EnvSpec", "GymnasiumEnv", "Box"]

EnvSpec = _core.EnvSpec
_OPTIONS = ("box_clock",)


def env_ids():
    """Every environment id, sorted."""
    return _core.env_ids()


def _split_options(kwargs):
    """(options, environment parameters) of a keyword-argument dict."""
    options = {key: value for key, value in kwargs.items() if key in _OPTIONS}
    parameters = {key: value for key, value in kwargs.items() if key not in _OPTIONS}
    return options, parameters


def describe(env_id=None, **parameters):
    """The resolved description of ``env_id`` with ``parameters`` applied, as a
    dict of key to text (as ``bsg envs --describe`` prints it)."""
    return dict(_core.describe(env_id, parameters))


class Env(_core.Env):
    """One environment with Safety-Gymnasium's API.

    ``reset(seed=None, options=None) -> (obs, info)``;
    ``step(action) -> (obs, reward, cost, terminated, truncated, info)`` where
    ``info`` maps every cost term of the task to its value. ``seed=None``
    continues the environment's random stream (seed 0 if it was never seeded).
    Options: ``box_clock="episode_phase"`` (default) or ``"simulated"``.
    """

    metadata = {"render_modes": []}
    render_mode = None

    def __init__(self, env_id=None, **kwargs):
        options, parameters = _split_options(kwargs)
        super().__init__(env_id, parameters=parameters, **options)
        spec = self.spec
        self.observation_space = box(
            -spec.observation_bound, spec.observation_bound, (spec.observation_dim,))
        self.action_space = box(spec.action_low, spec.action_high, (spec.action_dim,))

    @property
    def unwrapped(self):
        return self

    def render(self):
        raise NotImplementedError("bsg environments do not render")

    def __enter__(self):
        return self

    def __exit__(self, *exc_info):
        self.close()

    def __repr__(self):
        return f"<bsg.Env {self.spec.id}{' (closed)' if self.closed else ''}>"


class VectorEnv(_core.VectorEnv):
    """``num_envs`` environments of one id stepped on a C++ thread pool.

    ``num_threads=0`` uses every hardware thread (at most ``num_envs``). The
    GIL is released while the environments step. Environment ``i`` is reset
    with ``seed + i``; results are identical whatever ``num_threads`` is.
    ``step(actions[num_envs, act_dim])`` returns batched arrays and resets
    every environment whose episode ended: its ``obs`` row is then the first
    observation of the new episode and ``info["final_observation"]`` holds the
    step's own observations (``info["_final_observation"]`` marks the rows
    that were reset). ``info`` also holds one ``[num_envs]`` array per cost
    term.
    """

    def __init__(self, env_id=None, num_envs=1, num_threads=0, seed=0, **kwargs):
        options, parameters = _split_options(kwargs)
        super().__init__(env_id, num_envs, num_threads, seed, parameters=parameters, **options)
        spec = self.spec
        self.single_observation_space = box(
            -spec.observation_bound, spec.observation_bound, (spec.observation_dim,))
        self.single_action_space = box(spec.action_low, spec.action_high, (spec.action_dim,))
        self.observation_space = box(
            -spec.observation_bound, spec.observation_bound, (num_envs, spec.observation_dim))
        self.action_space = box(spec.action_low, spec.action_high, (num_envs, spec.action_dim))

    def __enter__(self):
        return self

    def __exit__(self, *exc_info):
        self.close()

    def __repr__(self):
        return (f"<bsg.VectorEnv {self.spec.id} x{self.num_envs} on {self.num_threads} "
                f"thread(s){' (closed)' if self.closed else ''}>")


def make(env_id=None, *, api="safety", **kwargs):
    """Makes environment ``env_id`` (see ``env_ids()``).

    ``api="safety"`` (default): Safety-Gymnasium's 6-tuple step;
    ``api="gymnasium"``: gymnasium's 5-tuple with the cost in ``info["cost"]``.
    Other keyword arguments change the description: ``make(id, bombs=12)``,
    ``make(agent="Drone", task="Reach")`` (no id: that agent on that task).
    Unknown ids raise ValueError listing the valid ones.
    """
    if env_id is not None and not isinstance(env_id, str):
        raise TypeError(f"env_id must be a str, got {type(env_id).__name__}")
    if api not in ("safety", "gymnasium"):
        raise ValueError(f"api must be 'safety' or 'gymnasium', got {api!r}")
    env = Env(env_id, **kwargs)
    return GymnasiumEnv(env) if api == "gymnasium" else env
