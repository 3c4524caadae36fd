"""``bsg.Env``: one environment with Safety-Gymnasium's 6-tuple step, and the
checks of arguments that ``Env`` and ``VectorEnv`` share.

Below every other module of the package but ``spaces``, ``rendering`` and
``gymnasium_support`` (docs/python.md#the-package): it imports none of the others.
"""

from . import _core
from . import rendering as _rendering
from .spaces import box

EnvSpec = _core.EnvSpec
_OPTIONS = ("box_clock",)


def env_ids():
    """Every environment id, sorted."""
    return _core.env_ids()


def split_options(kwargs):
    """(options, environment parameters) of a keyword-argument dict."""
    options = {key: value for key, value in kwargs.items() if key in _OPTIONS}
    parameters = {key: value for key, value in kwargs.items() if key not in _OPTIONS}
    return options, parameters


def describe(env_id=None, **parameters):
    """The resolved description of ``env_id`` with ``parameters`` applied, as a
    dict of key to text (as ``bsg envs --describe`` prints it)."""
    return dict(_core.describe(env_id, parameters))


def check_max_episode_steps(max_episode_steps):
    """ValueError unless ``max_episode_steps`` is None or an int >= 1."""
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
        options, parameters = split_options(kwargs)
        check_max_episode_steps(max_episode_steps)
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
        return (restore_env, (type(self), self._env_id,
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


def restore_env(cls, env_id, options, max_episode_steps, history):
    """What unpickling an ``Env`` calls: a new environment replaying ``history``."""
    env = cls(env_id, **options)
    env._max_episode_steps = max_episode_steps
    env._replay(history)
    return env
