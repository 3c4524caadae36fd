"""Gymnasium's ``EnvSpec`` of a bsg environment: what ``spec`` says on a
``GymnasiumEnv`` and on a ``VectorEnv`` with ``api="gymnasium"``.

The entry points are named by text ("bsg.registration:make_registered_env"),
so this module needs nothing above ``env``; ``registration`` registers the
specs that ``gymnasium_spec`` then reads back.
"""

import dataclasses

from .env import describe, split_options
from .gymnasium_support import IS_1X
from .gymnasium_support import gymnasium as _gymnasium

NAMESPACE = "bsg"
ENTRY_POINT = "bsg.registration:make_registered_env"
VECTOR_ENTRY_POINT = "bsg.registration:make_registered_vector_env"


def registered_id(env_id):
    """``"bsg/<env_id>"``, the id under which gymnasium knows ``env_id``."""
    return f"{NAMESPACE}/{env_id}"


def gymnasium_spec(env_id, options, max_episode_steps=None):
    """gymnasium's EnvSpec of ``env_id`` made with ``options`` (and another
    episode length if ``max_episode_steps`` is given), or None without
    gymnasium. ``env_id`` None (an agent on a task, ``bsg.make(agent=...,
    task=...)``) gives an unregistered spec whose entry point remakes the same
    environment."""
    if _gymnasium is None:
        return None
    if env_id is None:
        described = describe(**split_options(options)[1])
        # Gymnasium 0.x's make_vec passes no keywords to a vector entry point,
        # so only 1.x can remake an unregistered combination as a vector env.
        spec = _gymnasium.envs.registration.EnvSpec(
            id=registered_id(described["name"]), entry_point=ENTRY_POINT,
            vector_entry_point=VECTOR_ENTRY_POINT if IS_1X else None,
            max_episode_steps=int(described["max_episode_steps"]), kwargs={"env_id": None})
    else:
        spec = _gymnasium.spec(registered_id(env_id))
    changes = {"kwargs": {**spec.kwargs, **options}}
    if max_episode_steps is not None:
        changes["max_episode_steps"] = max_episode_steps
    return dataclasses.replace(spec, **changes)
