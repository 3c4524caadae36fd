"""Python rollouts are bit-identical to C++ ones for all 16 environments.

Oracles: bsg_trajectory_recorder (the same seeds and actions played in C++
straight through envs/env.h; every observation, reward, cost, flag and cost
term compared as raw 64-bit patterns) and `bsg rollout --json` (episode
returns, costs and lengths of the zero policy).
"""

import json
import subprocess

import numpy as np
import pytest

import bsg

IDS = bsg.env_ids()
STEPS = 260
RESET_EVERY = 110  # also exercises reset() continuing the random stream


def python_record(env_id, seed, actions):
    """The recorder's layout (tests/python/trajectory_recorder.cpp), from Python."""
    env = bsg.make(env_id)
    obs, _ = env.reset(seed=seed)
    record = [obs]
    since_reset = 0
    for action in actions:
        obs, reward, cost, terminated, truncated, info = env.step(action)
        record += [obs, [reward, cost, float(terminated), float(truncated)],
                   list(info.values())]
        since_reset += 1
        if terminated or truncated or since_reset == RESET_EVERY:
            obs, _ = env.reset()
            record.append(obs)
            since_reset = 0
    env.close()
    return np.concatenate([np.asarray(part, dtype=np.float64) for part in record])


@pytest.mark.parametrize("env_id", IDS)
def test_python_rollout_is_bit_identical_to_cpp(env_id, trajectory_recorder, tmp_path):
    seed = 1000 + IDS.index(env_id)
    act_dim = bsg.make(env_id).spec.action_dim
    actions = np.random.default_rng(seed).uniform(-1.2, 1.2, (STEPS, act_dim))
    actions_file = tmp_path / "actions.bin"
    output_file = tmp_path / "trajectory.bin"
    actions.tofile(actions_file)
    subprocess.run([trajectory_recorder, env_id, str(seed), str(RESET_EVERY),
                    str(actions_file), str(output_file)], check=True)
    cpp = np.fromfile(output_file, dtype=np.float64)
    python = python_record(env_id, seed, actions)
    assert python.shape == cpp.shape
    differing = np.flatnonzero(python.view(np.uint64) != cpp.view(np.uint64))
    assert differing.size == 0, f"{differing.size} values differ, first at {differing[:5]}"


@pytest.mark.parametrize("env_id", IDS)
def test_zero_policy_episodes_match_bsg_rollout(env_id, bsg_binary):
    seed = 7
    out = subprocess.run([bsg_binary, "rollout", "--env", env_id, "--policy", "zero",
                          "--episodes", "2", "--seed", str(seed), "--json"],
                         check=True, capture_output=True, text=True).stdout
    expected = json.loads(out)["episodes"]
    env = bsg.make(env_id)
    action = np.zeros(env.action_space.shape)
    for k, episode in enumerate(expected):
        env.reset(seed=seed if k == 0 else None)
        total_reward = total_cost = 0.0
        length = 0
        done = False
        while not done:
            _, reward, cost, terminated, truncated, _ = env.step(action)
            total_reward += reward
            total_cost += cost
            length += 1
            done = terminated or truncated
        assert (total_reward, total_cost, length) == (
            episode["return"], episode["cost"], episode["length"]), f"episode {k}"
