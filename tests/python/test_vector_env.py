"""bsg.VectorEnv: environment i plays what bsg.make(id) reset with seed + i
plays (the oracle: single environments stepped by hand, resetting as
Gymnasium 1.x's autoreset modes say), whatever the number of threads;
final_obs/final_info, the _key masks, seeds, seed lists and reset_mask."""

import numpy as np
import pytest

import bsg

STEPS = 300


def actions_for(num_envs, act_dim, steps, seed=0):
    return np.random.default_rng(seed).uniform(-1, 1, (steps, num_envs, act_dim))


def play_vector(env_id, num_envs, num_threads, seed, actions, mode="NextStep"):
    with bsg.VectorEnv(env_id, num_envs, num_threads=num_threads, seed=seed,
                       autoreset_mode=mode) as vector:
        obs, _ = vector.reset()
        trace = [obs]
        for batch in actions:
            obs, reward, cost, terminated, truncated, info = vector.step(batch)
            trace.append((obs, reward, cost, terminated, truncated, info))
        return trace


def info_columns(rows, mask):
    """Gymnasium's SyncVectorEnv info of these rows: a float64 column per key
    (0 where masked out) and its bool mask; no key when nothing reports."""
    info = {}
    if not mask.any():
        return info
    for name in next(row for row, keep in zip(rows, mask) if keep):
        info[name] = np.array([row[name] if keep else 0.0 for row, keep in zip(rows, mask)])
        info["_" + name] = mask.copy()
    return info


def play_singles(env_id, num_envs, seed, actions, mode="NextStep"):
    envs = [bsg.make(env_id) for _ in range(num_envs)]
    obs = np.stack([env.reset(seed=seed + i)[0] for i, env in enumerate(envs)])
    trace = [obs]
    pending = np.zeros(num_envs, bool)  # next-step: reset by this step
    for batch in actions:
        rows = []
        for i, (env, action) in enumerate(zip(envs, batch)):
            if pending[i]:
                rows.append((env.reset()[0], 0.0, 0.0, False, False, {}))
            else:
                rows.append(env.step(action))
        terminated = np.array([row[3] for row in rows])
        truncated = np.array([row[4] for row in rows])
        ended = terminated | truncated
        reported = ~pending
        if mode == "SameStep":
            reported = ~ended
            obs = np.stack([env.reset()[0] if end else row[0]
                            for env, row, end in zip(envs, rows, ended)])
        else:
            obs = np.stack([row[0] for row in rows])
            pending = ended
        info = info_columns([row[5] for row in rows], reported)
        if mode == "SameStep" and ended.any():
            info["final_obs"] = np.array([row[0] if end else None for row, end in zip(rows, ended)]
                                         + [None], dtype=object)[:-1]
            info["_final_obs"] = ended
            info["final_info"] = info_columns([row[5] for row in rows], ended)
            info["_final_info"] = ended
        trace.append((obs, np.array([row[1] for row in rows]), np.array([row[2] for row in rows]),
                      terminated, truncated, info))
    return trace


def assert_same_info(x, y, where):
    assert x.keys() == y.keys(), where
    for name in x:
        if isinstance(x[name], dict):
            assert_same_info(x[name], y[name], f"{where}[{name!r}]")
        elif x[name].dtype == object:
            assert len(x[name]) == len(y[name])
            for a, b in zip(x[name], y[name]):
                assert (a is None and b is None) or np.array_equal(a, b), f"{where}[{name!r}]"
        else:
            assert x[name].dtype == y[name].dtype, f"{where}[{name!r}]"
            assert np.array_equal(x[name], y[name]), f"{where}[{name!r}]"


def assert_same_trace(a, b):
    assert np.array_equal(a[0], b[0])
    for t, (x, y) in enumerate(zip(a[1:], b[1:])):
        for k in range(5):
            assert np.array_equal(x[k], y[k]), f"step {t}, tuple entry {k}"
            assert x[k].dtype == y[k].dtype
        assert_same_info(x[5], y[5], f"step {t}, info")


@pytest.mark.parametrize("mode", ["NextStep", "SameStep"])
@pytest.mark.parametrize("num_threads", [1, 2])
def test_environment_i_plays_a_single_env_seeded_with_seed_plus_i(num_threads, mode):
    # BallRun's episodes end early (leaving the corridor) or after 250 steps.
    actions = actions_for(3, 2, STEPS, seed=1)
    singles = play_singles("SafetyBallRun-v0", 3, 40, actions, mode)
    ended = sum((step[3] | step[4]).sum() for step in singles[1:])
    assert ended >= 3, "the test must cross auto-resets"
    assert_same_trace(play_vector("SafetyBallRun-v0", 3, num_threads, 40, actions, mode), singles)


@pytest.mark.parametrize("env_id", ["SafetyCarGather-v0", "SafetyAntRun-v0"])
def test_one_and_two_threads_give_identical_results(env_id):
    act_dim = bsg.make(env_id).spec.action_dim
    actions = actions_for(4, act_dim, 120, seed=2)
    assert_same_trace(play_vector(env_id, 4, 1, 9, actions), play_vector(env_id, 4, 2, 9, actions))


def test_same_step_rows_hold_the_new_episode_and_info_the_final_observation():
    with bsg.VectorEnv("SafetyBallCircle-v0", 2, num_threads=2, seed=0,
                       autoreset_mode="SameStep") as vector:
        vector.reset()
        zeros = np.zeros((2, 2))
        for step in range(1, 251):
            obs, _, _, terminated, truncated, info = vector.step(zeros)
            if step < 250:
                assert "final_obs" not in info and info["_cost_outside_bounds"].all()
        # Step 250 truncates both (max_episode_steps of BallCircle).
        assert truncated.all() and not terminated.any()
        assert info["_final_obs"].all() and info["_final_info"].all()
        assert "cost_outside_bounds" not in info  # the step's info moved to final_info
        assert info["final_info"]["_cost_outside_bounds"].all()
        oracle = bsg.make("SafetyBallCircle-v0")
        oracle.reset(seed=0)
        for _ in range(250):
            final = oracle.step(np.zeros(2))[0]
        assert np.array_equal(info["final_obs"][0], final)
        assert np.array_equal(obs[0], oracle.reset()[0])


def test_next_step_keeps_the_final_observation_and_resets_in_the_next_step():
    with bsg.VectorEnv("SafetyBallCircle-v0", 2, seed=0, max_episode_steps=5) as vector:
        vector.reset()
        for _ in range(5):
            obs, reward, cost, terminated, truncated, info = vector.step(np.zeros((2, 2)))
        assert truncated.all() and "final_obs" not in info
        oracle = bsg.make("SafetyBallCircle-v0")
        oracle.reset(seed=0)
        for _ in range(5):
            final = oracle.step(np.zeros(2))[0]
        assert np.array_equal(obs[0], final)
        obs, reward, cost, terminated, truncated, info = vector.step(np.ones((2, 2)))
        assert np.array_equal(obs[0], oracle.reset()[0])
        assert not reward.any() and not cost.any() and not (terminated | truncated).any()
        assert info == {}  # nobody stepped: the resets' infos are empty


def test_reset_seeds_are_fresh_starts_lists_and_masks():
    env_id = "SafetyCarReach-v0"

    def fresh(seed):
        return bsg.make(env_id).reset(seed=seed)[0]

    with bsg.VectorEnv(env_id, 3, seed=5) as vector:
        first, _ = vector.reset()            # the constructor's seed
        for _ in range(30):
            vector.step(np.full((3, 2), 0.7))
        again, _ = vector.reset(seed=5)      # after a history: still a fresh start
        assert np.array_equal(vector.reset(seed=np.array([8, 6, 2]))[0][0], fresh(8))
        listed, _ = vector.reset(seed=[8, None, 2])
        vector.step(np.full((3, 2), 0.7))
        stepped = vector.step(np.full((3, 2), 0.7))[0]
        masked, _ = vector.reset(seed=[None, 4, None],
                                 options={"reset_mask": np.array([False, True, False])})
    for i in range(3):
        assert np.array_equal(first[i], fresh(5 + i))
        assert np.array_equal(again[i], fresh(5 + i))
    assert np.array_equal(listed[0], fresh(8)) and np.array_equal(listed[2], fresh(2))
    single = bsg.make(env_id)
    single.reset(seed=6)
    assert np.array_equal(listed[1], single.reset()[0])  # None continues its stream
    assert np.array_equal(masked[1], fresh(4))
    assert np.array_equal(masked[[0, 2]], stepped[[0, 2]])  # untouched rows
    assert not np.array_equal(first[0], first[1])


def test_shapes_dtypes_spaces_and_metadata():
    with bsg.VectorEnv("SafetyDroneGather-v0", 5, num_threads=2) as vector:
        spec = vector.bsg_spec
        assert vector.num_envs == 5 and vector.num_threads == 2
        assert vector.single_observation_space.shape == (spec.observation_dim,)
        assert vector.observation_space.shape == (5, spec.observation_dim)
        assert vector.action_space.shape == (5, spec.action_dim)
        assert vector.metadata["render_fps"] == 60  # 1 / (1/60 s per step)
        assert str(getattr(vector.metadata["autoreset_mode"], "value",
                           vector.metadata["autoreset_mode"])) == "NextStep"
        obs, info = vector.reset()
        assert obs.shape == (5, spec.observation_dim) and obs.dtype == np.float64 and info == {}
        obs, reward, cost, terminated, truncated, info = vector.step(vector.action_space.sample())
        assert obs.shape == (5, spec.observation_dim)
        assert reward.shape == cost.shape == (5,) and reward.dtype == cost.dtype == np.float64
        assert terminated.dtype == truncated.dtype == np.bool_
        assert info["cost_gathered_bombs"].shape == (5,) and info["_cost_gathered_bombs"].all()
        assert vector.get_attr("max_episode_steps") == (500,) * 5


def test_gymnasium_api_returns_five_tuple_with_cost_in_info():
    actions = actions_for(2, 2, 40, seed=3)
    with bsg.VectorEnv("SafetyBallGather-v0", 2, seed=1) as safety, \
            bsg.VectorEnv("SafetyBallGather-v0", 2, seed=1, api="gymnasium") as gym:
        assert np.array_equal(safety.reset()[0], gym.reset()[0])
        for batch in actions:
            obs, reward, cost, terminated, truncated, info = safety.step(batch)
            result = gym.step(batch)
            assert len(result) == 5
            assert np.array_equal(result[0], obs) and np.array_equal(result[1], reward)
            assert np.array_equal(result[4]["cost"], cost) and result[4]["_cost"].all()


def test_vector_env_refuses_copies_and_bad_reset_options():
    import pickle
    with bsg.VectorEnv("SafetyBallRun-v0", 2) as vector:
        with pytest.raises(TypeError, match="cannot be pickled"):
            pickle.dumps(vector)
        with pytest.raises(TypeError, match="reset_mask.*numpy array"):
            vector.reset(options={"reset_mask": [True, False]})
        with pytest.raises(ValueError, match=r"shape `\(2,\)`"):
            vector.reset(options={"reset_mask": np.array([True])})
        with pytest.raises(ValueError, match="at least one True"):
            vector.reset(options={"reset_mask": np.zeros(2, bool)})
        with pytest.raises(ValueError, match="length must match num_envs=2"):
            vector.reset(seed=[1, 2, 3])
        with pytest.raises(ValueError, match="only the option 'reset_mask'"):
            vector.reset(options={"foo": 1})
    with pytest.raises(ValueError, match="autoreset_mode"):
        bsg.VectorEnv("SafetyBallRun-v0", 2, autoreset_mode="Disabled")
    with pytest.raises(ValueError, match="max_episode_steps must be an int >= 1"):
        bsg.VectorEnv("SafetyBallRun-v0", 2, max_episode_steps=0)
    with pytest.raises(ValueError, match="api must be"):
        bsg.VectorEnv("SafetyBallRun-v0", 2, api="gym")
