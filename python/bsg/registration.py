"""Registers every bsg environment with gymnasium as ``bsg/<id>``.

``import bsg`` calls ``register_all()`` when gymnasium is importable, so that

    gymnasium.make("bsg/SafetyBallCircle-v0")
    gymnasium.make_vec("bsg/SafetyBallCircle-v0", num_envs=8)   # bsg.VectorEnv

work with gymnasium's own options: ``max_episode_steps`` (gymnasium's
TimeLimit truncates, ``-1``: never), ``render_mode``, ``disable_env_checker``,
and make_vec's ``vectorization_mode`` ("vector_entry_point", the default, is
``bsg.VectorEnv``; "sync" and "async" are gymnasium's own over single bsg
environments). Every other keyword goes to ``bsg.make`` / ``bsg.VectorEnv``
unchanged. The entry points are module-level functions, so the specs pickle.
"""

import dataclasses

from . import spaces as _spaces

_gymnasium = _spaces._gymnasium
NAMESPACE = "bsg"


def registered_id(env_id):
    """``"bsg/<env_id>"``, the id under which gymnasium knows ``env_id``."""
    return f"{NAMESPACE}/{env_id}"


def make_registered_env(env_id, **overrides):
    """gymnasium.make's entry point: a ``GymnasiumEnv`` over ``bsg.make(env_id, **overrides)``.

    The environment does not truncate by itself: gymnasium.make wraps it in a
    TimeLimit of the registered length (or of its ``max_episode_steps``).
    """
    from . import make
    from .gymnasium_env import GymnasiumEnv
    for option in ("api", "autoreset"):
        if option in overrides:
            raise TypeError(f"gymnasium.make does not take bsg.make's option {option!r} (wrap "
                            f"the environment in gymnasium.wrappers.Autoreset to reset it)")
    env = make(env_id, **overrides)
    env._max_episode_steps = 0
    return GymnasiumEnv(env)


def make_registered_vector_env(env_id, num_envs=1, max_episode_steps=None, render_mode=None,
                               **options):
    """gymnasium.make_vec's vector entry point: a ``bsg.VectorEnv`` with gymnasium's 5-tuple."""
    from .vector import VectorEnv
    if render_mode is not None:
        options["render_mode"] = render_mode
    if max_episode_steps == -1:
        raise ValueError("bsg.VectorEnv always truncates: max_episode_steps=-1 is not supported "
                         "(use vectorization_mode='sync' for episodes without a time limit)")
    return VectorEnv(env_id, num_envs, api="gymnasium", max_episode_steps=max_episode_steps,
                     **options)


def register_all():
    """Registers ``bsg/<id>`` for every id (a no-op for ids already registered)."""
    from . import describe, env_ids
    from .gymnasium_env import GymnasiumEnv
    make_registered_env.metadata = GymnasiumEnv.metadata  # what gymnasium.make checks
    for env_id in env_ids():
        name = registered_id(env_id)
        if name in _gymnasium.envs.registry:
            continue
        _gymnasium.register(
            id=name,
            entry_point=f"{__name__}:make_registered_env",
            vector_entry_point=f"{__name__}:make_registered_vector_env",
            max_episode_steps=int(describe(env_id)["max_episode_steps"]),
            kwargs={"env_id": env_id},
        )


def gymnasium_spec(env_id, options, max_episode_steps=None):
    """gymnasium's EnvSpec of ``env_id`` made with ``options`` (and another
    episode length if ``max_episode_steps`` is given). ``env_id`` None (an
    agent on a task, ``bsg.make(agent=..., task=...)``) gives an unregistered
    spec whose entry point remakes the same environment."""
    if env_id is None:
        from . import _split_options, describe
        described = describe(**_split_options(options)[1])
        spec = _gymnasium.envs.registration.EnvSpec(
            id=registered_id(described["name"]), entry_point=f"{__name__}:make_registered_env",
            vector_entry_point=f"{__name__}:make_registered_vector_env",
            max_episode_steps=int(described["max_episode_steps"]), kwargs={"env_id": None})
    else:
        spec = _gymnasium.spec(registered_id(env_id))
    changes = {"kwargs": {**spec.kwargs, **options}}
    if max_episode_steps is not None:
        changes["max_episode_steps"] = max_episode_steps
    return dataclasses.replace(spec, **changes)
