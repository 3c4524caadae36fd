#!/usr/bin/python3
"""Logs the return and cost of every finished episode of a bsg.VectorEnv
stepped with random actions. The vector env resets finished environments by
itself, as Gymnasium 1.x does by default ("NextStep"): the step after an
episode's end starts the next episode (reward and cost 0), so it is not
counted.

    PYTHONPATH=build/release/python /usr/bin/python3 examples/python/vector_episodes.py \\
        [--env SafetyCarGather-v0] [--num-envs 8] [--episodes 16] [--threads 0]
"""

import argparse
import time

import numpy as np

import bsg

parser = argparse.ArgumentParser()
parser.add_argument("--env", default="SafetyCarGather-v0")
parser.add_argument("--num-envs", type=int, default=8)
parser.add_argument("--episodes", type=int, default=16)
parser.add_argument("--threads", type=int, default=0, help="0: one per hardware thread")
parser.add_argument("--seed", type=int, default=0)
args = parser.parse_args()

rng = np.random.default_rng(args.seed)
with bsg.VectorEnv(args.env, args.num_envs, num_threads=args.threads, seed=args.seed) as envs:
    print(f"{envs!r}, cost limit {envs.spec.cost_limit} per episode")
    envs.reset()
    returns = np.zeros(args.num_envs)
    costs = np.zeros(args.num_envs)
    resetting = np.zeros(args.num_envs, bool)  # envs whose next step is a reset
    finished = steps = 0
    start = time.perf_counter()
    while finished < args.episodes:
        actions = rng.uniform(-1, 1, envs.action_space.shape)
        obs, reward, cost, terminated, truncated, info = envs.step(actions)
        returns[resetting] = costs[resetting] = 0.0
        returns += reward
        costs += cost
        steps += args.num_envs
        resetting = terminated | truncated
        for i in np.flatnonzero(resetting):
            print(f"episode {finished:3d} (env {i}): return {returns[i]:9.3f}  cost {costs[i]:5.0f}"
                  f"  {'terminated' if terminated[i] else 'truncated'}")
            finished += 1
    print(f"{steps} steps in {time.perf_counter() - start:.2f} s")
