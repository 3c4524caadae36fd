#!/usr/bin/python3
"""bsg.VectorEnv against gymnasium.vector.SyncVectorEnv over the same bsg
environments, printed (never asserted): batch steps of N environments with the
same seeded random actions, Gymnasium's 5-tuple and next-step autoreset on both
sides.

- sync:  SyncVectorEnv of gymnasium.make("bsg/<id>", disable_env_checker=True)
         (gymnasium.make_vec's "sync" mode without its checker);
- bsg:   bsg.VectorEnv(id, N, api="gymnasium", num_threads=1), the same work on
         the same single thread, so the ratio is what the C++ pool saves and
         not extra cores; a second figure with num_threads=0 (every core).

Rounds alternate between the sides, so that a change in machine load hits
both; ratios are of process CPU time per batch step (waiting for a core is
not counted), medians over rounds, with the load average.

    PYTHONPATH=build/release/python:<gymnasium> /usr/bin/python3 \\
        python/bench/gymnasium_vector_bench.py [--ids ...] [--num-envs 16] [--steps 300] \\
        [--rounds 5]
"""

import argparse
import os
import statistics
import time

import numpy as np

import gymnasium

import bsg


def seconds(vector, actions, clock):
    """`clock` seconds for the batch steps of `actions` after a seeded reset."""
    vector.reset(seed=0)
    start = clock()
    for batch in actions:
        vector.step(batch)
    return clock() - start


def measure(env_id, num_envs, steps, rounds):
    sync = gymnasium.vector.SyncVectorEnv(
        [lambda: gymnasium.make(f"bsg/{env_id}", disable_env_checker=True)
         for _ in range(num_envs)])
    ours = bsg.VectorEnv(env_id, num_envs, api="gymnasium", num_threads=1)
    pooled = bsg.VectorEnv(env_id, num_envs, api="gymnasium", num_threads=0)
    act_dim = ours.single_action_space.shape[0]
    actions = np.random.default_rng(0).uniform(-1, 1, (steps, num_envs, act_dim))
    cpu_ratio, wall_ratio, sync_rate, ours_rate, pooled_rate = [], [], [], [], []
    for _ in range(rounds):
        s = seconds(sync, actions, time.process_time)
        o = seconds(ours, actions, time.process_time)
        cpu_ratio.append(s / o)
        sync_rate.append(steps * num_envs / s)
        ours_rate.append(steps * num_envs / o)
        ws = seconds(sync, actions, time.perf_counter)
        wp = seconds(pooled, actions, time.perf_counter)
        wall_ratio.append(ws / wp)
        pooled_rate.append(steps * num_envs / wp)
    print(f"{env_id:22s} sync {statistics.median(sync_rate):9.0f} steps/s, bsg 1 thread "
          f"{statistics.median(ours_rate):9.0f} steps/s: {statistics.median(cpu_ratio):.2f}x "
          f"(CPU time; rounds {min(cpu_ratio):.2f}-{max(cpu_ratio):.2f}x) | bsg "
          f"{pooled.num_threads} threads {statistics.median(pooled_rate):9.0f} steps/s wall: "
          f"{statistics.median(wall_ratio):.2f}x")
    for vector in (sync, ours, pooled):
        vector.close()


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--ids", nargs="+", default=["SafetyBallCircle-v0", "SafetyCarCircle-v0",
                                                     "SafetyDroneReach-v0", "SafetyAntRun-v0"])
    parser.add_argument("--num-envs", type=int, default=16)
    parser.add_argument("--steps", type=int, default=300)
    parser.add_argument("--rounds", type=int, default=5)
    args = parser.parse_args()
    print(f"{args.num_envs} environments, {args.steps} batch steps x {args.rounds} rounds, "
          f"load average {', '.join(f'{x:.2f}' for x in os.getloadavg())}")
    for env_id in args.ids:
        measure(env_id, args.num_envs, args.steps, args.rounds)
    print(f"done, load average {', '.join(f'{x:.2f}' for x in os.getloadavg())}")


if __name__ == "__main__":
    main()
