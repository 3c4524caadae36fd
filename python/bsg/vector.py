"""``bsg.VectorEnv``: N environments of one id stepped on a C++ thread pool.

An object says what it is: ``bsg.VectorEnv(id, n)`` (bsg's API, the 6-tuple
step) is no ``gymnasium.vector.VectorEnv``, while ``bsg.VectorEnv(id, n,
api="gymnasium")`` is a ``GymnasiumVectorEnv``, a subclass that is one and keeps
the contract of the importable Gymnasium: 1.x's (5-tuple, ``autoreset_mode``
next-step or same-step with ``final_obs``) or 0.28/0.29's (5-tuple, same-step
autoreset with ``final_observation`` and ``final_info``, ``step_async`` and
``step_wait``). docs/python.md#vector-environments describes the API.
"""

import numpy as np

from . import _core
from . import rendering as _rendering
from .env import check_max_episode_steps, split_options
from .gymnasium_support import IS_1X
from .gymnasium_support import gymnasium as _gymnasium
from .spaces import box
from .specs import gymnasium_spec

_AutoresetMode = _gymnasium.vector.AutoresetMode if IS_1X else None
_MODES = {"NextStep": True, "SameStep": False}  # name -> next-step?


def _next_step(autoreset_mode, api):
    """True for next-step autoreset; accepts gymnasium's AutoresetMode or its value.
    None is the default of the API: Gymnasium 0.x's vector API resets in the same step."""
    if autoreset_mode is None:
        return not (api == "gymnasium" and _gymnasium is not None and not IS_1X)
    value = getattr(autoreset_mode, "value", autoreset_mode)
    if value not in _MODES:
        raise ValueError(f"autoreset_mode must be 'NextStep' or 'SameStep' (or gymnasium's "
                         f"AutoresetMode of them), got {autoreset_mode!r}")
    if api == "gymnasium" and _gymnasium is not None and not IS_1X and value == "NextStep":
        raise ValueError(f"Gymnasium {_gymnasium.__version__}'s vector environments reset in the "
                         f"same step; autoreset_mode='NextStep' with api='gymnasium' needs "
                         f"Gymnasium 1.x (api='safety' resets in the next step under any version)")
    return _MODES[value]


class VectorEnv(_core.VectorEnv):
    """``num_envs`` environments of one id stepped on a C++ thread pool.

    ``VectorEnv(id, num_envs, num_threads=0, seed=0, api="safety",
    autoreset_mode=None, max_episode_steps=None, **options)``.
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
    Ended episodes are reset as Gymnasium 1.x defines it: ``"NextStep"`` by
    the next step, which returns the new episode's first
    observation with reward 0 and both flags false; ``"SameStep"`` in the
    step itself, whose observation row is then the new episode's while
    ``info["final_obs"]`` and ``info["final_info"]`` hold the ended episode's
    last observation and info. ``info`` holds one ``[N]`` array per cost term
    with its ``"_<key>"`` mask of the environments that reported it.

    With gymnasium importable, ``api="gymnasium"`` makes a
    ``GymnasiumVectorEnv`` (a subclass that is a ``gymnasium.vector.VectorEnv``);
    ``autoreset_mode=None`` is ``"NextStep"`` except there under Gymnasium 0.x,
    whose vector API resets in the same step.
    """

    def __new__(cls, *args, api="safety", **kwargs):
        if cls is VectorEnv and api == "gymnasium" and GymnasiumVectorEnv is not None:
            cls = GymnasiumVectorEnv
        return _core.VectorEnv.__new__(cls)

    def __init__(self, env_id=None, num_envs=1, num_threads=0, seed=0, *, api="safety",
                 autoreset_mode=None, max_episode_steps=None, render_mode=None,
                 width=480, height=360, camera="default", **kwargs):
        if api not in ("safety", "gymnasium"):
            raise ValueError(f"api must be 'safety' or 'gymnasium', got {api!r}")
        next_step = _next_step(autoreset_mode, api)
        check_max_episode_steps(max_episode_steps)
        options, parameters = split_options(kwargs)
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
        self._spec = (gymnasium_spec(env_id, kwargs) if api == "gymnasium" else None) or spec

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


def _seed_np_random(env, seed):
    """Seeds ``env.np_random`` as gymnasium's VectorEnv.reset does for an int seed."""
    if isinstance(seed, (int, np.integer)) and not isinstance(seed, bool):
        env._np_random, env._np_random_seed = _gymnasium.utils.seeding.np_random(int(seed))


def _legacy_final_keys(info, num_envs):
    """Gymnasium 0.x's same-step keys from 1.x's: ``final_observation`` and
    ``final_info`` (an object array of each ended environment's info dict,
    None for the others), each with its mask, as 0.x's SyncVectorEnv gives them."""
    if "final_obs" not in info:
        return info
    ended = info.pop("_final_obs")
    final_obs = info.pop("final_obs")
    columns = info.pop("final_info")
    info.pop("_final_info")
    final_info = np.full(num_envs, None, dtype=object)
    for i in np.flatnonzero(ended):
        final_info[i] = {key: values[i].item() for key, values in columns.items()
                         if not key.startswith("_") and columns[f"_{key}"][i]}
    info["final_observation"], info["_final_observation"] = final_obs, ended
    info["final_info"], info["_final_info"] = final_info, ended.copy()
    return info


if _gymnasium is None:
    GymnasiumVectorEnv = None
elif IS_1X:
    class GymnasiumVectorEnv(VectorEnv, _gymnasium.vector.VectorEnv):
        """``bsg.VectorEnv(..., api="gymnasium")`` under Gymnasium 1.x: a
        ``gymnasium.vector.VectorEnv`` whose ``step`` is the 5-tuple and whose
        ``metadata["autoreset_mode"]`` is the mode it resets in."""

        def __init__(self, env_id=None, num_envs=1, num_threads=0, seed=0, *, api="gymnasium",
                     **kwargs):
            if api != "gymnasium":
                raise ValueError(f"GymnasiumVectorEnv has gymnasium's API, got api={api!r}")
            super().__init__(env_id, num_envs, num_threads, seed, api=api, **kwargs)

        def reset(self, *, seed=None, options=None):
            _seed_np_random(self, seed)
            return _core.VectorEnv.reset(self, seed=seed, options=options)
else:
    class GymnasiumVectorEnv(VectorEnv, _gymnasium.vector.VectorEnv):
        """``bsg.VectorEnv(..., api="gymnasium")`` under Gymnasium 0.28 or 0.29:
        a ``gymnasium.vector.VectorEnv`` of that version, which resets an ended
        episode in the same step and reports its last observation and info as
        ``info["final_observation"]`` and ``info["final_info"]``."""

        is_vector_env = True

        def __init__(self, env_id=None, num_envs=1, num_threads=0, seed=0, *, api="gymnasium",
                     **kwargs):
            if api != "gymnasium":
                raise ValueError(f"GymnasiumVectorEnv has gymnasium's API, got api={api!r}")
            super().__init__(env_id, num_envs, num_threads, seed, api=api, **kwargs)
            self._pending_actions = self._pending_reset = None

        def reset(self, *, seed=None, options=None):
            _seed_np_random(self, seed)
            return _core.VectorEnv.reset(self, seed=seed, options=options)

        def step(self, actions):
            obs, reward, terminated, truncated, info = _core.VectorEnv.step(self, actions)
            return obs, reward, terminated, truncated, _legacy_final_keys(info, self.num_envs)

        # Gymnasium 0.x's VectorEnv and its wrappers step and reset in two halves.
        def step_async(self, actions):
            self._pending_actions = actions

        def step_wait(self, **kwargs):
            if self._pending_actions is None:
                raise RuntimeError("step_wait() without a step_async(actions) before it")
            actions, self._pending_actions = self._pending_actions, None
            return self.step(actions)

        def reset_async(self, seed=None, options=None):
            self._pending_reset = dict(seed=seed, options=options)

        def reset_wait(self, seed=None, options=None, **kwargs):
            pending, self._pending_reset = self._pending_reset, None
            return self.reset(**(pending or dict(seed=seed, options=options)))
