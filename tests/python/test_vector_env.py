"""bsg.VectorEnv: environment i plays what bsg.make(id) reset with seed + i
plays (the oracle: single environments stepped by hand, resetting when an
episode ends), whatever the number of threads; auto-reset and seeds."""

import numpy as np
import pytest

import bsg

STEPS = 300


def actions_for(num_envs, act_dim, steps, seed=0):
    return np.random.default_rng(seed).uniform(-1, 1, (steps, num_envs, act_dim))


def play_vector(env_id, num_envs, num_threads, seed, actions):
    with bsg.VectorEnv(env_id, num_envs, num_threads=num_threads, seed=seed) as vector:
        obs, _ = vector.reset()
        trace = [obs]
        for batch in actions:
            obs, reward, cost, terminated, truncated, info = vector.step(batch)
            trace.append((obs, reward, cost, terminated, truncated, info))
        return trace


def play_singles(env_id, num_envs, seed, actions):
    envs = [bsg.make(env_id) for _ in range(num_envs)]
    obs = np.stack([env.reset(seed=seed + i)[0] for i, env in enumerate(envs)])
    trace = [obs]
    for batch in actions:
        rows = [env.step(action) for env, action in zip(envs, batch)]
        final = np.stack([row[0] for row in rows])
        ended = np.array([row[3] or row[4] for row in rows])
        obs = np.stack([env.reset()[0] if end else row[0]
                        for env, row, end in zip(envs, rows, ended)])
        info = {name: np.array([row[5][name] for row in rows]) for name in rows[0][5]}
        info["final_observation"] = final
        info["_final_observation"] = ended
        trace.append((obs, np.array([row[1] for row in rows]), np.array([row[2] for row in rows]),
                      np.array([row[3] for row in rows]), np.array([row[4] for row in rows]),
                      info))
    return trace


def assert_same_trace(a, b):
    assert np.array_equal(a[0], b[0])
    for t, (x, y) in enumerate(zip(a[1:], b[1:])):
        for k in range(5):
            assert np.array_equal(x[k], y[k]), f"step {t}, tuple entry {k}"
            assert x[k].dtype == y[k].dtype
        assert x[5].keys() == y[5].keys()
        for name in x[5]:
            assert np.array_equal(x[5][name], y[5][name]), f"step {t}, info[{name!r}]"


@pytest.mark.parametrize("num_threads", [1, 2])
def test_environment_i_plays_a_single_env_seeded_with_seed_plus_i(num_threads):
    # BallRun's episodes end early (leaving the corridor) or after 250 steps.
    actions = actions_for(3, 2, STEPS, seed=1)
    singles = play_singles("SafetyBallRun-v0", 3, 40, actions)
    ended = sum(step[5]["_final_observation"].sum() for step in singles[1:])
    assert ended >= 3, "the test must cross auto-resets"
    assert_same_trace(play_vector("SafetyBallRun-v0", 3, num_threads, 40, actions), singles)


@pytest.mark.parametrize("env_id", ["SafetyCarGather-v0", "SafetyAntRun-v0"])
def test_one_and_two_threads_give_identical_results(env_id):
    act_dim = bsg.make(env_id).spec.action_dim
    actions = actions_for(4, act_dim, 120, seed=2)
    assert_same_trace(play_vector(env_id, 4, 1, 9, actions), play_vector(env_id, 4, 2, 9, actions))


def test_auto_reset_rows_hold_the_new_episode_and_info_the_final_observation():
    with bsg.VectorEnv("SafetyBallCircle-v0", 2, num_threads=2, seed=0) as vector:
        vector.reset()
        zeros = np.zeros((2, 2))
        for step in range(1, 251):
            obs, _, _, terminated, truncated, info = vector.step(zeros)
            if step < 250:
                assert not info["_final_observation"].any()
                assert np.array_equal(info["final_observation"], obs)
        # Step 250 truncates both (max_episode_steps of BallCircle).
        assert truncated.all() and not terminated.any()
        assert info["_final_observation"].all()
        oracle = bsg.make("SafetyBallCircle-v0")
        oracle.reset(seed=0)
        for _ in range(250):
            final = oracle.step(np.zeros(2))[0]
        assert np.array_equal(info["final_observation"][0], final)
        assert np.array_equal(obs[0], oracle.reset()[0])


def test_reset_seeds():
    # A reset is not a pure function of its seed: as in the original suite,
    # later resets restore the first reset's snapshot and motor targets
    # survive them. The oracle is therefore single environments given the
    # same history: reset(seed + i), reset(seed + i), reset().
    env_id = "SafetyCarReach-v0"
    with bsg.VectorEnv(env_id, 3, seed=5) as vector:
        first, _ = vector.reset()            # the constructor's seed
        again, _ = vector.reset(seed=5)
        continued, _ = vector.reset()        # each stream continues
    for i in range(3):
        single = bsg.make(env_id)
        assert np.array_equal(first[i], single.reset(seed=5 + i)[0])
        assert np.array_equal(again[i], single.reset(seed=5 + i)[0])
        assert np.array_equal(continued[i], single.reset()[0])
    assert not np.array_equal(first[0], first[1])


def test_shapes_dtypes_and_spaces():
    with bsg.VectorEnv("SafetyDroneGather-v0", 5, num_threads=2) as vector:
        spec = vector.spec
        assert vector.num_envs == 5 and vector.num_threads == 2
        assert vector.single_observation_space.shape == (spec.observation_dim,)
        assert vector.observation_space.shape == (5, spec.observation_dim)
        assert vector.action_space.shape == (5, spec.action_dim)
        obs, info = vector.reset()
        assert obs.shape == (5, spec.observation_dim) and obs.dtype == np.float64 and info == {}
        obs, reward, cost, terminated, truncated, info = vector.step(vector.action_space.sample())
        assert obs.shape == (5, spec.observation_dim)
        assert reward.shape == cost.shape == (5,) and reward.dtype == cost.dtype == np.float64
        assert terminated.dtype == truncated.dtype == np.bool_
        assert info["final_observation"].shape == obs.shape
        assert info["cost_gathered_bombs"].shape == (5,)
