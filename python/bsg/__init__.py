"""bsg: the 16 Bullet-Safety-Gym environments from C++, for Python.

    import bsg
    env = bsg.make("SafetyBallCircle-v0")
    obs, info = env.reset(seed=0)
    obs, reward, cost, terminated, truncated, info = env.step(env.action_space.sample())

``bsg.env_ids()`` lists the ids; ``bsg.VectorEnv(id, num_envs)`` steps many
environments on a C++ thread pool; ``bsg.make(id, api="gymnasium")`` gives
gymnasium's 5-tuple with the cost in ``info["cost"]``. ``render_mode="rgb_array"``
makes ``env.render()`` return frames (``bsg.rendering``).
"""

from . import _core
from . import rendering as _rendering
from .spaces import Box, box
from .wrappers import GymnasiumEnv

__all__ = ["make", "env_ids", "Env", "VectorEnv", "EnvSpec", "GymnasiumEnv", "Box"]

EnvSpec = _core.EnvSpec
_OPTIONS = ("box_clock",)


def env_ids():
    """Every environment id, sorted."""
    return _core.env_ids()


def _check_options(options):
    unknown = sorted(set(options) - set(_OPTIONS))
    if unknown:
        raise TypeError(f"unknown option(s) {unknown}; valid options: {list(_OPTIONS)}")


class Env(_core.Env):
    """One environment with Safety-Gymnasium's API.

    ``reset(seed=None, options=None) -> (obs, info)``;
    ``step(action) -> (obs, reward, cost, terminated, truncated, info)`` where
    ``info`` maps every cost term of the task to its value. ``seed=None``
    continues the environment's random stream (seed 0 if it was never seeded).
    Options: ``box_clock="episode_phase"`` (default) or ``"simulated"``.
    """

    metadata = _rendering.METADATA
    render_mode = None

    def __init__(self, env_id, render_mode=None, width=480, height=360, camera="default",
                 **options):
        _check_options(options)
        renderer = _rendering.make_renderer(render_mode, width, height, camera)
        super().__init__(env_id, **options)
        self.render_mode = render_mode
        self._renderer = renderer
        spec = self.spec
        self.observation_space = box(
            -spec.observation_bound, spec.observation_bound, (spec.observation_dim,))
        self.action_space = box(spec.action_low, spec.action_high, (spec.action_dim,))

    @property
    def unwrapped(self):
        return self

    def render(self):
        """The current frame: [height, width, 3] uint8 (render_mode="rgb_array")
        or [height, width] float32 metres ("depth_array")."""
        return _rendering.render(self, self._renderer)

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

    metadata = _rendering.METADATA
    render_mode = None

    def __init__(self, env_id, num_envs, num_threads=0, seed=0, render_mode=None, width=480,
                 height=360, camera="default", **options):
        _check_options(options)
        renderer = _rendering.make_renderer(render_mode, width, height, camera)
        super().__init__(env_id, num_envs, num_threads, seed, **options)
        self.render_mode = render_mode
        self._renderer = renderer
        spec = self.spec
        self.single_observation_space = box(
            -spec.observation_bound, spec.observation_bound, (spec.observation_dim,))
        self.single_action_space = box(spec.action_low, spec.action_high, (spec.action_dim,))
        self.observation_space = box(
            -spec.observation_bound, spec.observation_bound, (num_envs, spec.observation_dim))
        self.action_space = box(spec.action_low, spec.action_high, (num_envs, spec.action_dim))

    def render(self):
        """Every environment's frame, rendered on the pool's threads:
        [num_envs, height, width, 3] uint8 (or [num_envs, height, width] float32)."""
        return _rendering.render(self, self._renderer, vector=True)

    def __enter__(self):
        return self

    def __exit__(self, *exc_info):
        self.close()

    def __repr__(self):
        return (f"<bsg.VectorEnv {self.spec.id} x{self.num_envs} on {self.num_threads} "
                f"thread(s){' (closed)' if self.closed else ''}>")


def make(env_id, *, api="safety", **options):
    """Makes environment ``env_id`` (see ``env_ids()``).

    ``api="safety"`` (default): Safety-Gymnasium's 6-tuple step;
    ``api="gymnasium"``: gymnasium's 5-tuple with the cost in ``info["cost"]``.
    ``render_mode="rgb_array"`` (or ``"depth_array"``), ``width=480``,
    ``height=360``, ``camera="default"`` (or ``"track"``, ``"top"``) make
    ``render()`` return frames. Unknown ids raise ValueError listing the valid ones.
    """
    if not isinstance(env_id, str):
        raise TypeError(f"env_id must be a str, got {type(env_id).__name__}")
    if api not in ("safety", "gymnasium"):
        raise ValueError(f"api must be 'safety' or 'gymnasium', got {api!r}")
    env = Env(env_id, **options)
    return GymnasiumEnv(env) if api == "gymnasium" else env
