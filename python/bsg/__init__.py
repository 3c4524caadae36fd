"""bsg: the 16 Bullet-Safety-Gym environments from C++, for Python.

    import bsg
    env = bsg.make("SafetyBallCircle-v0")
    obs, info = env.reset(seed=0)
    obs, reward, cost, terminated, truncated, info = env.step(env.action_space.sample())

``bsg.env_ids()`` lists the ids; ``bsg.VectorEnv(id, num_envs)`` steps many
environments on a C++ thread pool; ``bsg.make(id, api="gymnasium")`` gives
gymnasium's 5-tuple with the cost in ``info["cost"]``. When gymnasium is
importable, ``import bsg`` registers every id as ``bsg/<id>`` for
``gymnasium.make`` and ``gymnasium.make_vec`` (docs/python.md).
``render_mode="rgb_array"`` makes ``env.render()`` return frames (``bsg.rendering``).

Every other keyword argument changes a parameter of the environment's
description (``bsg.describe(id)`` lists them, docs/environments.md):
``bsg.make("SafetyBallGather-v0", bombs=12)``, or a new combination
``bsg.make(agent="Drone", task="Reach", zones=4)``; the same for
``bsg.VectorEnv``. A bad key or value raises ValueError naming it.
"""

from . import _core
from . import rendering as _rendering
from .spaces import Box, _gymnasium, box
from .gymnasium_env import GymnasiumEnv
from .wrappers import NextStepAutoreset

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


def _check_max_episode_steps(max_episode_steps):
    if max_episode_steps is not None and (isinstance(max_episode_steps, bool) or
                                          not isinstance(max_episode_steps, int) or
                                          max_episode_steps < 1):
        raise ValueError(f"max_episode_steps must be an int >= 1 or None, got "
                         f"{max_episode_steps!r}")


class Env(_core.Env):
    """One environment with Safety-Gymnasium's API.

    ``reset(seed=None, options=None) -> (obs, info)``;
    ``step(action) -> (obs, reward, cost, terminated, truncated, info)`` where
    ``info`` maps every cost term of the task to its value. ``reset(seed=s)``
    is a fresh start: the same episode for the same seed and actions whatever
    the environment did before; ``seed=None`` continues the environment's
    random stream (seed 0 if it was never seeded). ``max_episode_steps``
    (default: the spec's) truncates episodes after that many steps.
    Options: ``box_clock="episode_phase"`` (default) or ``"simulated"``.
    Actions outside [-1, 1] are clipped by the Ball, Drone and Ant and used as
    given by the Car, as in the original; the first one warns. ``pickle`` and
    ``copy.deepcopy`` give an independent environment in the same state.
    """

    metadata = _rendering.METADATA
    render_mode = None

    def __init__(self, env_id=None, *, max_episode_steps=None, render_mode=None, width=480,
                 height=360, camera="default", **kwargs):
        options, parameters = _split_options(kwargs)
        _check_max_episode_steps(max_episode_steps)
        renderer = _rendering.make_renderer(render_mode, width, height, camera)
        super().__init__(env_id, parameters=parameters, **options)
        self.render_mode = render_mode
        self._renderer = renderer
        self._env_id = env_id  # what a copy or gymnasium's spec remakes (None: agent and task)
        self._options = dict(kwargs)
        self._render_options = (dict(render_mode=render_mode, width=width, height=height,
                                     camera=camera) if render_mode is not None else {})
        if max_episode_steps is not None:
            self._max_episode_steps = max_episode_steps
        spec = self.spec
        self.observation_space = box(
            -spec.observation_bound, spec.observation_bound, (spec.observation_dim,))
        self.action_space = box(spec.action_low, spec.action_high, (spec.action_dim,))

    @property
    def unwrapped(self):
        return self

    @property
    def bsg_spec(self):
        """The same as ``spec``: bsg's ``EnvSpec``."""
        return self.spec

    def render(self):
        """The current frame: [height, width, 3] uint8 (render_mode="rgb_array")
        or [height, width] float32 metres ("depth_array")."""
        return _rendering.render(self, self._renderer)

    def __reduce__(self):
        # A copy replays what this environment did since its last seeded
        # reset (python/src/episode_history.h): Bullet has no full snapshot.
        return (_restore_env, (type(self), self._env_id,
                               {**self._options, **self._render_options},
                               self._max_episode_steps, self._history()))

    def __enter__(self):
        return self

    def __exit__(self, *exc_info):
        self.close()

    def __repr__(self):
        if "_options" not in self.__dict__:  # __init__ raised before the C++ env existed
            return "<bsg.Env (not constructed)>"
        return f"<bsg.Env {self.spec.id}{' (closed)' if self.closed else ''}>"


def _restore_env(cls, env_id, options, max_episode_steps, history):
    env = cls(env_id, **options)
    env._max_episode_steps = max_episode_steps
    env._replay(history)
    return env


from .vector import VectorEnv  # noqa: E402  (needs Env's module to be complete)


def make(env_id=None, *, api="safety", max_episode_steps=None, autoreset=False,
         disable_env_checker=None, **options):
    """Makes environment ``env_id`` (see ``env_ids()``).

    ``api="safety"`` (default): Safety-Gymnasium's 6-tuple step;
    ``api="gymnasium"``: gymnasium's 5-tuple with the cost in ``info["cost"]``.
    ``max_episode_steps``: truncation length (default: the spec's);
    ``autoreset=True``: an ended episode is reset by the next step
    (``NextStepAutoreset``, or gymnasium's ``Autoreset`` for ``api="gymnasium"``
    when gymnasium is importable); ``disable_env_checker`` is accepted for
    gymnasium's and Safety-Gymnasium's callers and changes nothing (bsg.make
    adds no checker). ``render_mode="rgb_array"`` (or ``"depth_array"``),
    ``width=480``, ``height=360``, ``camera="default"`` (or ``"track"``,
    ``"top"``) make ``render()`` return frames. Other keyword arguments change
    the description: ``make(id, bombs=12)``, ``make(agent="Drone",
    task="Reach")`` (no id: that agent on that task). Unknown ids raise
    ValueError listing the valid ones.
    """
    if env_id is not None and not isinstance(env_id, str):
        raise TypeError(f"env_id must be a str, got {type(env_id).__name__}")
    if api not in ("safety", "gymnasium"):
        raise ValueError(f"api must be 'safety' or 'gymnasium', got {api!r}")
    if not isinstance(autoreset, bool):
        raise TypeError(f"autoreset must be a bool, got {autoreset!r}")
    if disable_env_checker is not None and not isinstance(disable_env_checker, bool):
        raise TypeError(f"disable_env_checker must be a bool or None, got {disable_env_checker!r}")
    env = Env(env_id, max_episode_steps=max_episode_steps, **options)
    if api == "gymnasium":
        env = GymnasiumEnv(env)
        if autoreset and _gymnasium is not None:
            return _gymnasium.wrappers.Autoreset(env)  # the same rule, as a gymnasium.Wrapper
    return NextStepAutoreset(env) if autoreset else env


if _gymnasium is not None and hasattr(_gymnasium.vector, "AutoresetMode"):  # gymnasium 1.x
    from . import registration  # noqa: E402
    registration.register_all()
