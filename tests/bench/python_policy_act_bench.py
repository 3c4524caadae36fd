#!/usr/bin/env python3
"""What acting costs from Python (docs/python.md#use-a-trained-policy): bsg.load_policy's act on a
batch of 1 and of 1,024 observations, beside a PyTorch MLP of the same shape (the run's
hidden_sizes and activation, its observation standardisation, the mean action's tanh-free output
layer) on one thread, float64 as bsg computes and float32 as PyTorch users usually run. Prints
microseconds per call (the median of rounds) and per observation. Optional: torch is not a
dependency of bsg; where it is missing its lines say SKIPPED.

Usage: PYTHONPATH=build/release/python /usr/bin/python3 tests/bench/python_policy_act_bench.py [RUN_DIR]
Without RUN_DIR it first trains a one-epoch PPO-Lag run on SafetyBallCircle-v0 (64-64 tanh) in a
temporary folder: the weights do not change the cost of acting.
"""
import json
import os
import statistics
import sys
import tempfile
import time

# One thread everywhere: Debian's torch calls the system BLAS, whose own pool torch.set_num_threads
# does not govern.
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")

import numpy as np  # noqa: E402

import bsg  # noqa: E402

ROUNDS = 15
ROUND_SECONDS = 0.2


def microseconds_per_call(call):
    """The median over ROUNDS of the mean time of a call, each round ROUND_SECONDS long."""
    calls = 1
    while True:  # calls per round: enough to fill ROUND_SECONDS
        start = time.perf_counter()
        for _ in range(calls):
            call()
        if time.perf_counter() - start >= ROUND_SECONDS / 4:
            break
        calls *= 2
    calls *= 4
    rounds = []
    for _ in range(ROUNDS):
        start = time.perf_counter()
        for _ in range(calls):
            call()
        rounds.append((time.perf_counter() - start) / calls * 1e6)
    return statistics.median(rounds)


def report(name, batch, micros):
    print(f"  {name:34s} batch {batch:5d}: {micros:10.2f} us per call, {micros / batch:8.3f} us per observation")


def torch_policy(torch, observation_size, action_size, hidden_sizes, activation, normalization, dtype):
    """The same shape: standardise and clip, hidden layers, a linear mean."""
    layers = []
    width = observation_size
    for hidden in hidden_sizes:
        layers += [torch.nn.Linear(width, hidden), torch.nn.Tanh() if activation == "tanh" else torch.nn.ReLU()]
        width = hidden
    layers.append(torch.nn.Linear(width, action_size))
    net = torch.nn.Sequential(*layers).to(dtype)
    mean = std = clip = None
    if normalization is not None:
        mean = torch.tensor(normalization["mean"], dtype=dtype)
        std = torch.tensor(normalization["std"], dtype=dtype) + normalization["std_epsilon"]
        clip = normalization["clip"]

    def act(observations):
        with torch.no_grad():
            x = torch.from_numpy(observations)
            if mean is not None:
                x = (x - mean) / std
                if clip is not None:
                    x = x.clamp(-clip, clip)
            return net(x).numpy()

    return act


def main():
    with tempfile.TemporaryDirectory() as scratch:
        if len(sys.argv) > 1:
            run_dir = sys.argv[1]
        else:
            run_dir = bsg.train({"env_id": "SafetyBallCircle-v0", "alg": "ppo-lag", "epochs": 1,
                                 "steps_per_epoch": 1000, "eval_episodes": 0}, out=os.path.join(scratch, "run"),
                                verbose=False)
        policy = bsg.load_policy(run_dir)
        config = policy.config
        hidden_sizes = json.loads(config["hidden_sizes"])
        activation = config["activation"]
        observation_size = policy.observation_space.shape[0]
        action_size = policy.action_space.shape[0]
        print(f"policy: {policy.alg} on {policy.env_id}, {observation_size} -> {hidden_sizes} {activation} -> "
              f"{action_size}; median of {ROUNDS} rounds of {ROUND_SECONDS} s")
        env = bsg.make(policy.env_id)
        rng = np.random.default_rng(0)
        observations = []  # observations the environment gives, under random actions
        obs, _ = env.reset(seed=0)
        for _ in range(1024):
            observations.append(obs)
            obs, *_ = env.step(rng.uniform(-1.0, 1.0, action_size))
        env.close()
        batches = {1: np.array(observations[:1]), 1024: np.array(observations)}

        for batch, data in batches.items():
            report("bsg Policy.act (float64)", batch, microseconds_per_call(lambda: policy.act(data)))
        single = batches[1][0]
        report("bsg Policy.act, one [obs_dim]", 1, microseconds_per_call(lambda: policy.act(single)))

        try:
            import torch
        except ImportError:
            print("  torch SKIPPED: PyTorch is not installed (Debian: python3-torch)")
            return
        torch.set_num_threads(1)
        torch.manual_seed(0)
        for dtype, label in ((torch.float64, "float64"), (torch.float32, "float32")):
            act = torch_policy(torch, observation_size, action_size, hidden_sizes, activation,
                               policy.observation_normalization, dtype)
            for batch, data in batches.items():
                typed = data.astype(np.float64 if dtype == torch.float64 else np.float32)
                report(f"torch {torch.__version__} MLP ({label})", batch, microseconds_per_call(lambda: act(typed)))


if __name__ == "__main__":
    main()
