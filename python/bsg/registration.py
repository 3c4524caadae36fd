"""Registers every bsg environment with gymnasium as ``bsg/<id>``.

``import bsg`` calls ``register_all()`` when Gymnasium 0.28, 0.29 or 1.x is
importable, so that

    gymnasium.make("bsg/SafetyBallCircle-v0")
    gymnasium.make_vec("bsg/SafetyBallCircle-v0", num_envs=8)   # 1.x: a bsg.VectorEnv

work with gymnasium's own options: ``max_episode_steps`` (gymnasium's
TimeLimit truncates, ``-1``: never), ``render_mode``, ``disable_env_checker``,
and make_vec's ``vectorization_mode`` (1.x: "vector_entry_point", the default,
is ``bsg.VectorEnv``; 0.x: "custom"; "sync" and "async" are gymnasium's own
over single bsg environments). Every other keyword goes to ``bsg.make`` /
``bsg.VectorEnv`` unchanged. The entry points are module-level functions
(under 0.x a ``VectorEntryPoint`` that names the id, since 0.x's make_vec
passes the environment's keywords to no vector entry point), so the specs
pickle and compare equal after a round trip.

The top of the package's Python files: it imports the others, none imports it.
"""

import dataclasses

from .env import describe, env_ids
from .gymnasium_env import GymnasiumEnv
from .gymnasium_support import IS_1X
from .gymnasium_support import registration as _gymnasium_registration
from .making import make
from .specs import ENTRY_POINT, VECTOR_ENTRY_POINT, registered_id
from .vector import VectorEnv


def make_registered_env(env_id, **overrides):
    """gymnasium.make's entry point: a ``GymnasiumEnv`` over ``bsg.make(env_id, **overrides)``.

    The environment does not truncate by itself: gymnasium.make wraps it in a
    TimeLimit of the registered length (or of its ``max_episode_steps``).
    """
    for option in ("api", "autoreset"):
        if option in overrides:
            raise TypeError(f"gymnasium.make does not take bsg.make's option {option!r} (wrap "
                            f"the environment in gymnasium.wrappers.Autoreset to reset it)")
    env = make(env_id, **overrides)
    env._max_episode_steps = 0
    return GymnasiumEnv(env)


make_registered_env.metadata = GymnasiumEnv.metadata  # what gymnasium.make checks


def make_registered_vector_env(env_id=None, num_envs=1, max_episode_steps=None, render_mode=None,
                               **options):
    """gymnasium.make_vec's vector entry point: a ``bsg.VectorEnv`` with gymnasium's 5-tuple."""
    if render_mode is not None:
        options["render_mode"] = render_mode
    if max_episode_steps == -1:
        raise ValueError("bsg.VectorEnv always truncates: max_episode_steps=-1 is not supported "
                         "(use vectorization_mode='sync' for episodes without a time limit)")
    return VectorEnv(env_id, num_envs, api="gymnasium", max_episode_steps=max_episode_steps,
                     **options)


@dataclasses.dataclass(frozen=True)
class VectorEntryPoint:
    """Gymnasium 0.x's vector entry point of one id: make_vec(id, vectorization_mode="custom")
    calls it with ``num_envs`` and ``max_episode_steps`` (and its ``vector_kwargs``) only."""

    env_id: str

    def __call__(self, **kwargs):
        return make_registered_vector_env(self.env_id, **kwargs)


def register_all():
    """Registers ``bsg/<id>`` for every id (a no-op for ids already registered).

    Also the Gymnasium plugin entry point of an installed bsg (``[gymnasium.envs] __root__ =
    bsg.registration:register_all``), which Gymnasium 0.28 and 0.29 call while they are imported,
    so that ``gymnasium.make("bsg/...")`` works in scripts that never import bsg.
    """
    for env_id in env_ids():
        name = registered_id(env_id)
        if name in _gymnasium_registration.registry:
            continue
        _gymnasium_registration.register(
            id=name,
            entry_point=ENTRY_POINT,
            vector_entry_point=(VECTOR_ENTRY_POINT if IS_1X else
                                VectorEntryPoint(env_id)),
            max_episode_steps=int(describe(env_id)["max_episode_steps"]),
            kwargs={"env_id": env_id},
        )
