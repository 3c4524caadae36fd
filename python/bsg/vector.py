"""``bsg.VectorEnv``: N environments of one id stepped on a C++ thread pool.

When gymnasium is importable it is a ``gymnasium.vector.VectorEnv``, so that
gymnasium's vector wrappers accept it (with ``api="gymnasium"``, whose step is
gymnasium's 5-tuple). docs/python.md#vector-environments describes the API.
"""

import numpy as np

from . import _core
from . import rendering as _rendering
from .spaces import _gymnasium, box

if _gymnasium is not None and hasattr(_gymnasium.vector, "AutoresetMode"):  # gymnasium 1.x
    from gymnasium.vector import AutoresetMode as _AutoresetMode
    _VectorBase = _gymnasium.vector.VectorEnv
else:
    _AutoresetMode = None
    _VectorBase = object

_MODES = {"NextStep": True, "SameStep": False}  # name -> next-step?


def _next_step(autoreset_mode):
    """True for next-step autoreset; accepts gymnasium's AutoresetMode or its value."""
    value = getattr(autoreset_mode, "value", autoreset_mode)
    if value not in _MODES:
        raise ValueError(f"autoreset_mode must be 'NextStep' or 'SameStep' (or gymnasium's "
                         f"AutoresetMode of them), got {autoreset_mode!r}")
    return _MODES[value]


class VectorEnv(_core.VectorEnv, _VectorBase):
    """``num_envs`` environments of one id stepped on a C++ thread pool.

    ``VectorEnv(id, num_envs, num_threads=0, seed=0, api="safety",
    autoreset_mode="NextStep", max_episode_steps=None, **options)``.
    ``num_threads=0`` uses every hardware thread (at most ``num_envs``); the
    GIL is released while the environments step, and results are identical
    whatever ``num_threads`` is.

    ``reset(seed=None, options=None)``: an int seeds environment i with
    ``seed + i``, a list gives one seed (or None) per environment, None
    continues each environment's stream (the constructor's ``seed + i`` at
    its first reset); a seed is a fresh start, as for ``bsg.Env``.
    ``options={"reset_mask": mask}`` resets only the environments where the
    ``[N]`` bool mask is True.

    ``step(actions[num_envs, act_dim])`` returns ``(obs, reward, cost,
    terminated, truncated, info)`` (``api="safety"``) or ``(obs, reward,
    terminated, truncated, info)`` with ``info["cost"]`` (``api="gymnasium"``).
    Ended episodes are reset as Gymnasium 1.x defines it: ``"NextStep"`` (the
    default) by the next step, which returns the new episode's first
    observation with reward 0 and both flags false; ``"SameStep"`` in the
    step itself, whose observation row is then the new episode's while
    ``info["final_obs"]`` and ``info["final_info"]`` hold the ended episode's
    last observation and info. ``info`` holds one ``[N]`` array per cost term
    with its ``"_<key>"`` mask of the environments that reported it.
    """

    def __init__(self, env_id=None, num_envs=1, num_threads=0, seed=0, *, api="safety",
                 autoreset_mode="NextStep", max_episode_steps=None, render_mode=None,
                 width=480, height=360, camera="default", **kwargs):
        if api not in ("safety", "gymnasium"):
            raise ValueError(f"api must be 'safety' or 'gymnasium', got {api!r}")
        next_step = _next_step(autoreset_mode)
        options, parameters = _check_arguments(kwargs, max_episode_steps)
        self._renderer = _rendering.make_renderer(render_mode, width, height, camera)
        super().__init__(env_id, num_envs, num_threads, seed, parameters=parameters, **options)
        self._configure(api == "gymnasium", next_step, max_episode_steps or 0)
        self.api = api
        self._options = dict(kwargs)
        spec = self.bsg_spec
        self.single_observation_space = box(
            -spec.observation_bound, spec.observation_bound, (spec.observation_dim,))
        self.single_action_space = box(spec.action_low, spec.action_high, (spec.action_dim,))
        self.observation_space = box(
            -spec.observation_bound, spec.observation_bound, (num_envs, spec.observation_dim))
        self.action_space = box(spec.action_low, spec.action_high, (num_envs, spec.action_dim))
        mode = "NextStep" if next_step else "SameStep"
        self.autoreset_mode = _AutoresetMode(mode) if _AutoresetMode is not None else mode
        self.metadata = {**_rendering.METADATA, "autoreset_mode": self.autoreset_mode}
        self.render_mode = render_mode
        self._spec = _gymnasium_spec(env_id, kwargs, api) or spec

    @property
    def bsg_spec(self):
        """bsg's ``EnvSpec`` of one environment."""
        return _core.VectorEnv.spec.__get__(self)

    @property
    def spec(self):
        """gymnasium's EnvSpec with ``api="gymnasium"`` and gymnasium importable, else bsg's."""
        return self._spec

    @spec.setter
    def spec(self, value):  # gymnasium.make_vec sets it
        self._spec = value

    def reset(self, *, seed=None, options=None):
        if _VectorBase is not object and isinstance(seed, (int, np.integer)) \
                and not isinstance(seed, bool):
            _VectorBase.reset(self, seed=int(seed))  # seeds self.np_random
        return _core.VectorEnv.reset(self, seed=seed, options=options)

    def render(self):
        """Every environment's frame, rendered on the pool's threads:
        [num_envs, height, width, 3] uint8 (render_mode="rgb_array") or
        [num_envs, height, width] float32 metres ("depth_array")."""
        return _rendering.render(self, self._renderer, vector=True)

    def call(self, name, *args, **kwargs):
        """``name`` of every environment: ``call("render")`` renders, an attribute
        (``spec``, ``observation_space``, ``metadata``, ...) is read."""
        if name == "render":
            return tuple(self.render(*args, **kwargs))
        return tuple(self._single_attribute(name) for _ in range(self.num_envs))

    def get_attr(self, name):
        """The attribute ``name`` of every environment, as a tuple."""
        return self.call(name)

    def set_attr(self, name, values):
        raise AttributeError(f"bsg.VectorEnv's environments live in C++; their attribute "
                             f"{name!r} cannot be set")

    def _single_attribute(self, name):
        single = {"observation_space": self.single_observation_space,
                  "action_space": self.single_action_space, "spec": self.spec,
                  "bsg_spec": self.bsg_spec, "metadata": self.metadata,
                  "render_mode": self.render_mode,
                  "max_episode_steps": self.max_episode_steps}
        if name not in single:
            raise AttributeError(f"bsg.VectorEnv cannot call or read {name!r} of its "
                                 f"environments; available: render, {', '.join(single)}")
        return single[name]

    def close(self, **kwargs):
        _core.VectorEnv.close(self)

    @property
    def closed(self):
        return _core.VectorEnv.closed.__get__(self)

    @closed.setter
    def closed(self, value):  # gymnasium's VectorEnv.close() sets it; the core knows
        pass

    def __reduce__(self):
        raise TypeError("a bsg.VectorEnv cannot be pickled or copied (its environments run on "
                        "a C++ thread pool); pickle its id and options and build a new one")

    def __enter__(self):
        return self

    def __exit__(self, *exc_info):
        self.close()

    def __del__(self):
        pass  # gymnasium's VectorEnv.__del__ would close; the core frees itself

    def __repr__(self):
        if "_options" not in self.__dict__:  # __init__ raised before the C++ envs existed
            return "<bsg.VectorEnv (not constructed)>"
        return (f"<bsg.VectorEnv {self.bsg_spec.id} x{self.num_envs} on {self.num_threads} "
                f"thread(s){' (closed)' if self.closed else ''}>")


def _check_arguments(kwargs, max_episode_steps):
    """(options, description parameters) of ``kwargs``, checked as ``Env`` checks them."""
    from . import _check_max_episode_steps, _split_options  # one check for Env and VectorEnv
    _check_max_episode_steps(max_episode_steps)
    return _split_options(kwargs)


def _gymnasium_spec(env_id, options, api):
    if _gymnasium is None or api != "gymnasium":
        return None
    from . import registration
    return registration.gymnasium_spec(env_id, options)
