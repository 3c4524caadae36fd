"""bsg: the 16 Bullet-Safety-Gym environments from C++, for Python.

    import bsg
    env = bsg.make("SafetyBallCircle-v0")
    obs, info = env.reset(seed=0)
    obs, reward, cost, terminated, truncated, info = env.step(env.action_space.sample())

``bsg.env_ids()`` lists the ids; ``bsg.VectorEnv(id, num_envs)`` steps many
environments on a C++ thread pool; ``bsg.make(id, api="gymnasium")`` gives
gymnasium's 5-tuple with the cost in ``info["cost"]``. When Gymnasium 0.28,
0.29 or 1.x is importable, ``import bsg`` registers every id as ``bsg/<id>``
for ``gymnasium.make`` and ``gymnasium.make_vec`` (docs/python.md).
``render_mode="rgb_array"`` makes ``env.render()`` return frames (``bsg.rendering``).

Every other keyword argument changes a parameter of the environment's
description (``bsg.describe(id)`` lists them, docs/environments.md):
``bsg.make("SafetyBallGather-v0", bombs=12)``, or a new combination
``bsg.make(agent="Drone", task="Reach", zones=4)``; the same for
``bsg.VectorEnv``. A bad key or value raises ValueError naming it.

The package's files import one way only, each from those below it
(docs/python.md#the-package): registration -> making, vector -> wrappers ->
gymnasium_env -> specs -> env -> spaces, rendering -> gymnasium_support -> datasets, _core;
parallel -> rendering, spaces; parallel_vector -> spaces; policies -> spaces; training -> _core.
``bsg.parallel_env(id)`` makes a multi-agent environment with PettingZoo's
Parallel API (``bsg.parallel_env_ids()``, docs/multi_agent.md);
``bsg.parallel_vector_env(id, num_envs)`` steps N of them on the thread pool.
``bsg.datasets`` reads offline datasets (DSRL's HDF5 layout, docs/datasets.md).
``bsg.load_policy(run_dir)`` gives a trained run's policy (``policy.act(obs)``) and
``bsg.evaluate(run_dir)`` its evaluation, as ``bsg eval`` (``bsg.policies``).
``bsg.train(config, out=...)`` trains a run in this process as ``bsg train`` does and
``bsg.sweep(grid)`` runs a grid as ``bsg sweep`` does (``bsg.training``).
This file imports them all and registers last.
"""

from . import _core
from . import datasets
from .env import Env, EnvSpec, describe, env_ids
from .env import restore_env as _restore_env  # noqa: F401  (what pickles of bsg.Env name)
from .gymnasium_env import GymnasiumEnv
from .gymnasium_support import gymnasium as _gymnasium
from .making import make
from .parallel import ParallelEnv, describe_parallel_env, parallel_env, parallel_env_ids
from .parallel_vector import ParallelVectorEnv, parallel_vector_env
from .policies import Policy, evaluate, load_policy
from .spaces import Box
from .training import sweep, train
from .vector import GymnasiumVectorEnv, VectorEnv
from .wrappers import NextStepAutoreset
from . import registration

__all__ = ["make", "describe", "env_ids", "Env", "VectorEnv", "GymnasiumVectorEnv", "EnvSpec",
           "GymnasiumEnv", "NextStepAutoreset", "Box", "load_policy", "evaluate", "Policy", "train", "sweep",
           "parallel_env", "parallel_env_ids", "describe_parallel_env", "ParallelEnv",
           "parallel_vector_env", "ParallelVectorEnv"]

if _gymnasium is not None:
    registration.register_all()
