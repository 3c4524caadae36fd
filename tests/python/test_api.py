"""API conformance of every environment: spaces, spec, the 6-tuple, the
gymnasium wrapper. Oracles: `bsg envs --json` for the spec, the declared
bounds of the original suite (actions in [-1, 1], observations within ±1000),
and a second environment with the same seed for the wrapper."""

import json
import subprocess

import numpy as np
import pytest

import bsg

IDS = bsg.env_ids()


@pytest.fixture(scope="module")
def catalogue(bsg_binary):
    out = subprocess.run([bsg_binary, "envs", "--json"], check=True, capture_output=True,
                         text=True).stdout
    return {entry["id"]: entry for entry in json.loads(out)}


def test_env_ids_are_the_sixteen_of_the_suite_and_their_fork_variants():
    expected = sorted(f"Safety{agent}{task}-{variant}" for agent in ("Ball", "Car", "Drone", "Ant")
                      for task in ("Circle", "Gather", "Reach", "Run") for variant in ("v0", "fork"))
    assert IDS == expected


@pytest.mark.parametrize("env_id", IDS)
def test_spec_and_spaces_match_bsg_envs(env_id, catalogue):
    entry = catalogue[env_id]
    with bsg.make(env_id) as env:
        spec = env.spec
        assert (spec.id, spec.agent, spec.task) == (env_id, entry["agent"], entry["task"])
        assert spec.max_episode_steps == entry["max_episode_steps"]
        assert spec.cost_limit == entry["cost_limit"]
        assert env.observation_space.shape == (entry["observation_dim"],)
        assert env.action_space.shape == (entry["action_dim"],)
        assert env.observation_space.dtype == np.float64
        assert env.action_space.dtype == np.float64
        assert np.all(env.action_space.low == -1) and np.all(env.action_space.high == 1)
        assert np.all(env.observation_space.low == -1000)
        assert np.all(env.observation_space.high == 1000)


@pytest.mark.parametrize("env_id", IDS)
def test_reset_and_step_follow_safety_gymnasium(env_id):
    env = bsg.make(env_id)
    env.action_space.seed(1)
    obs, info = env.reset(seed=3)
    assert isinstance(info, dict) and info == {}
    assert obs.shape == env.observation_space.shape and obs.dtype == np.float64
    for _ in range(20):
        result = env.step(env.action_space.sample())
        assert isinstance(result, tuple) and len(result) == 6
        obs, reward, cost, terminated, truncated, info = result
        assert obs.shape == env.observation_space.shape and obs.dtype == np.float64
        assert env.observation_space.contains(obs)
        assert type(reward) is float and type(cost) is float
        assert cost in (0.0, 1.0)
        assert type(terminated) is bool and type(truncated) is bool
        assert info and all(name.startswith(("cost_", "number_")) for name in info)
        assert all(type(value) is float for value in info.values())
        if terminated or truncated:
            env.reset()
    env.close()


def test_observation_is_a_fresh_array_each_step():
    env = bsg.make("SafetyBallCircle-v0")
    first, _ = env.reset(seed=0)
    kept = first.copy()
    second = env.step(np.full(2, 0.5))[0]
    assert np.array_equal(first, kept), "a returned observation changed after the next step"
    assert not np.array_equal(first, second)


def test_episode_is_truncated_at_max_episode_steps():
    env = bsg.make("SafetyBallCircle-v0")  # the zero action never leaves the arena
    env.reset(seed=0)
    steps = 0
    while True:
        _, _, _, terminated, truncated, _ = env.step(np.zeros(2))
        steps += 1
        assert not terminated
        if truncated:
            break
    assert steps == env.spec.max_episode_steps == 250


def test_same_seed_same_episode_and_seedless_reset_continues_the_stream():
    # Fresh environments: later resets restore the first one's snapshot, as
    # in the original suite, so only equal histories give equal resets.
    a, _ = bsg.make("SafetyCarReach-v0").reset(seed=11)
    b, _ = bsg.make("SafetyCarReach-v0").reset(seed=11)
    env = bsg.make("SafetyCarReach-v0")
    env.reset(seed=11)
    c, _ = env.reset()
    assert np.array_equal(a, b)
    assert not np.array_equal(a, c)


def test_gymnasium_wrapper_returns_five_tuple_with_cost_in_info():
    safety = bsg.make("SafetyBallGather-v0")
    gym = bsg.make("SafetyBallGather-v0", api="gymnasium")
    assert isinstance(gym, bsg.GymnasiumEnv) and gym.unwrapped is gym
    assert gym.bsg_spec.id == "SafetyBallGather-v0"
    assert gym.observation_space == safety.observation_space
    obs_a, _ = safety.reset(seed=5)
    obs_b, _ = gym.reset(seed=5)
    assert np.array_equal(obs_a, obs_b)
    rng = np.random.default_rng(0)
    for _ in range(60):
        action = rng.uniform(-1, 1, 2)
        obs_a, reward_a, cost_a, term_a, trunc_a, info_a = safety.step(action)
        result = gym.step(action)
        assert len(result) == 5
        obs_b, reward_b, term_b, trunc_b, info_b = result
        assert np.array_equal(obs_a, obs_b)
        assert (reward_a, term_a, trunc_a) == (reward_b, term_b, trunc_b)
        assert info_b["cost"] == cost_a
        assert {k: v for k, v in info_b.items() if k != "cost"} == info_a
    gym.close()
    with pytest.raises(RuntimeError, match="closed"):
        gym.step(np.zeros(2))


def test_box_fallback_samples_inside_and_contains():
    space = bsg.Box(-1.0, 1.0, (3,), seed=4)
    samples = np.array([space.sample() for _ in range(200)])
    assert samples.shape == (200, 3) and samples.dtype == np.float64
    assert samples.min() >= -1 and samples.max() <= 1 and samples.std() > 0.4
    assert space.contains(np.zeros(3)) and np.zeros(3) in space
    assert not space.contains(np.full(3, 1.5)) and not space.contains(np.zeros(2))


def test_spaces_are_gymnasium_boxes_when_gymnasium_is_importable():
    gymnasium = pytest.importorskip("gymnasium")
    env = bsg.make("SafetyBallCircle-v0", api="gymnasium")
    assert isinstance(env.action_space, gymnasium.spaces.Box)
    assert isinstance(env, gymnasium.Env)
