"""bsg as a Gymnasium 1.x environment, checked by the real Gymnasium:
gymnasium.make of every bsg/ id passes gymnasium's own check_env; gymnasium's
wrappers run full episodes over a bsg environment without warnings and keep
a spec; np_random is seeded as gymnasium seeds it. Oracles: gymnasium's
checker and wrappers themselves, numpy's default_rng for np_random, the
test's own sums of each episode's rewards for the episode statistics."""

import copy
import pickle
import warnings

from gymnasium_import import import_gymnasium

gymnasium = import_gymnasium()

import numpy as np  # noqa: E402
import pytest  # noqa: E402
from gymnasium.utils.env_checker import check_env  # noqa: E402

import bsg  # noqa: E402  (after gymnasium, so that bsg registers its ids)

IDS = bsg.env_ids()
# Documented (docs/python.md#the-single-environment): check_env warns whenever it is given a
# wrapped environment, which gymnasium.make always returns.
DOCUMENTED = ("is different from the unwrapped version",)


def core_renders():
    """Whether this build's environments render (bsg.make accepts render_mode)."""
    try:
        bsg.make("SafetyBallCircle-v0", render_mode="rgb_array").close()
        return True
    except (TypeError, ValueError, NotImplementedError):
        return False


def undocumented(caught):
    return [str(w.message) for w in caught
            if not any(text in str(w.message) for text in DOCUMENTED)]


@pytest.mark.parametrize("env_id", IDS)
def test_check_env_passes_through_gymnasium_make(env_id):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        env = gymnasium.make(f"bsg/{env_id}")
        assert isinstance(env.unwrapped, gymnasium.Env)
        assert isinstance(env.unwrapped, bsg.GymnasiumEnv)
        check_env(env, skip_render_check=not core_renders())
        check_env(env.unwrapped, skip_render_check=not core_renders())
        env.close()
    assert undocumented(caught) == []


def test_unwrapped_metadata_spec_and_np_random():
    env = gymnasium.make("bsg/SafetyDroneReach-v0")
    raw = env.unwrapped
    assert raw.unwrapped is raw
    assert raw.metadata == {"render_modes": ["rgb_array", "depth_array"], "render_fps": 60}
    assert env.spec.id == "bsg/SafetyDroneReach-v0" and env.spec.max_episode_steps == 500
    assert pickle.loads(pickle.dumps(env.spec)) == env.spec
    assert raw.bsg_spec.agent == "Drone" and raw.bsg_spec.cost_limit == 10
    env.reset(seed=3)
    assert raw.np_random.random() == np.random.default_rng(3).random()
    assert env.render_mode is None
    with pytest.warns(UserWarning, match="without specifying any render mode"):
        assert raw.render() is None


@pytest.mark.parametrize("env_id", IDS)
def test_same_seed_same_episode_after_any_history_through_gymnasium_make(env_id):
    env = gymnasium.make(f"bsg/{env_id}")
    env.action_space.seed(0)
    actions = [env.action_space.sample() for _ in range(40)]
    fresh = gymnasium.make(f"bsg/{env_id}")
    first = [fresh.reset(seed=21)[0]] + [fresh.step(a)[0] for a in actions]
    env.reset(seed=1)
    for _ in range(70):
        env.step(env.action_space.sample())
    env.reset()
    again = [env.reset(seed=21)[0]] + [env.step(a)[0] for a in actions]
    assert all(np.array_equal(a, b) for a, b in zip(first, again))


def test_direct_adapter_spec_says_its_episode_length_and_options():
    env = bsg.make("SafetyBallRun-v0", api="gymnasium", max_episode_steps=40,
                   box_clock="simulated")
    assert env.spec.max_episode_steps == 40 and env.spec.kwargs["box_clock"] == "simulated"
    remade = env.spec.make()  # gymnasium.make of the same spec
    remade.reset(seed=0)
    assert [remade.step(np.zeros(2))[3] for _ in range(40)] == [False] * 39 + [True]


def test_make_options_reach_bsg():
    env = gymnasium.make("bsg/SafetyBallCircle-v0", max_episode_steps=7, render_mode=None,
                         disable_env_checker=True, box_clock="simulated")
    assert env.spec.kwargs["box_clock"] == "simulated" and env.spec.max_episode_steps == 7
    env.reset(seed=0)
    flags = [env.step(np.zeros(2))[3] for _ in range(7)]
    assert flags == [False] * 6 + [True]
    longer = gymnasium.make("bsg/SafetyBallCircle-v0", max_episode_steps=300)  # beyond 250
    longer.reset(seed=0)
    assert not any(longer.step(np.zeros(2))[3] for _ in range(299))
    assert longer.step(np.zeros(2))[3]
    with pytest.raises(ValueError, match="unknown parameter"):
        gymnasium.make("bsg/SafetyBallCircle-v0", no_such_option=1)
    with pytest.raises(TypeError, match="gymnasium.wrappers.Autoreset"):
        # Under make's TimeLimit an inner autoreset would truncate every later step.
        gymnasium.make("bsg/SafetyBallCircle-v0", autoreset=True)
    vector = gymnasium.make_vec("bsg/SafetyBallRun-v0", num_envs=2, box_clock="simulated")
    assert isinstance(vector, bsg.VectorEnv) and isinstance(vector, gymnasium.vector.VectorEnv)
    assert vector.spec.id == "bsg/SafetyBallRun-v0"
    vector.close()


def episode(env, steps_cap=2000):
    """Plays one episode with seeded random actions; returns the last step."""
    env.action_space.seed(5)
    env.reset(seed=5)
    for _ in range(steps_cap):
        result = env.step(env.action_space.sample())
        if result[2] or result[3]:
            return result
    raise AssertionError("episode did not end")


WRAPPERS = {
    "TimeLimit": lambda env: gymnasium.wrappers.TimeLimit(env, 50),
    "RecordEpisodeStatistics": gymnasium.wrappers.RecordEpisodeStatistics,
    "NormalizeObservation": gymnasium.wrappers.NormalizeObservation,
    "NormalizeReward": gymnasium.wrappers.NormalizeReward,
    "ClipAction": gymnasium.wrappers.ClipAction,
    "RescaleAction": lambda env: gymnasium.wrappers.RescaleAction(env, 0.0, 1.0),
    "FlattenObservation": gymnasium.wrappers.FlattenObservation,
    "Autoreset": gymnasium.wrappers.Autoreset,
    "PassiveEnvChecker": gymnasium.wrappers.PassiveEnvChecker,
    "OrderEnforcing": gymnasium.wrappers.OrderEnforcing,
}


@pytest.mark.parametrize("name", sorted(WRAPPERS))
@pytest.mark.parametrize("env_id", ["SafetyBallCircle-v0", "SafetyAntRun-v0"])
def test_gymnasium_wrappers_run_a_full_episode_without_warnings(name, env_id):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        env = WRAPPERS[name](bsg.make(env_id, api="gymnasium"))
        assert env.spec is not None and env.spec.id == f"bsg/{env_id}"
        obs, reward, terminated, truncated, info = episode(env)
        assert "cost" in info
        if name == "TimeLimit":
            assert truncated and env.get_wrapper_attr("_elapsed_steps") == 50
        if name == "Autoreset":  # the next step resets
            obs, reward, terminated, truncated, info = env.step(env.action_space.sample())
            assert (reward, terminated, truncated) == (0.0, False, False)
        env.close()
    assert [str(w.message) for w in caught] == []


def test_record_episode_statistics_equal_the_episode_sums():
    env = gymnasium.wrappers.RecordEpisodeStatistics(bsg.make("SafetyCarRun-v0", api="gymnasium"))
    env.action_space.seed(1)
    env.reset(seed=1)
    total, length, cost = 0.0, 0, 0.0
    while True:
        obs, reward, terminated, truncated, info = env.step(env.action_space.sample())
        total, length, cost = total + reward, length + 1, cost + info["cost"]
        if terminated or truncated:
            break
    assert info["episode"]["r"] == pytest.approx(total, rel=1e-12, abs=1e-12)
    assert info["episode"]["l"] == length == 500


def test_pickle_and_deepcopy_of_a_gymnasium_made_env():
    env = gymnasium.make("bsg/SafetyAntCircle-v0")
    env.reset(seed=8)
    env.action_space.seed(8)
    for _ in range(20):
        env.step(env.action_space.sample())
    twins = [pickle.loads(pickle.dumps(env)), copy.deepcopy(env)]
    for _ in range(30):
        action = env.action_space.sample()
        expected = env.step(action)
        for twin in twins:
            result = twin.step(action)
            assert np.array_equal(result[0], expected[0]) and result[1:] == expected[1:]


def make_vector(kind, num_envs, **kwargs):
    if kind == "bsg":
        return bsg.VectorEnv("SafetyBallRun-v0", num_envs, seed=0, api="gymnasium", **kwargs)
    return gymnasium.make_vec("bsg/SafetyBallRun-v0", num_envs=num_envs, vectorization_mode=kind,
                              vector_kwargs=kwargs)


@pytest.mark.parametrize("kind", ["bsg", "sync", "async"])
def test_vector_wrappers_statistics_equal_the_episodes_own_sums(kind):
    normalized = gymnasium.wrappers.vector.NormalizeObservation(make_vector(kind, 3))
    env = gymnasium.wrappers.vector.RecordEpisodeStatistics(normalized)
    twin = make_vector(kind, 3)  # the same episodes, unnormalised
    rng = np.random.default_rng(0)
    raw = [twin.reset(seed=10)[0]]
    env.reset(seed=10)
    returns, lengths, pending = np.zeros(3), np.zeros(3, int), np.zeros(3, bool)
    checked = 0
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        for _ in range(600):
            actions = rng.uniform(-1, 1, (3, 2))
            obs, reward, terminated, truncated, info = env.step(actions)
            raw.append(twin.step(actions)[0])
            # Next-step autoreset: the step after an episode's end is a reset.
            returns[pending], lengths[pending] = 0.0, 0
            returns[~pending] += reward[~pending]
            lengths[~pending] += 1
            pending = terminated | truncated
            for i in np.flatnonzero(info.get("_episode", np.zeros(3, bool))):
                assert info["episode"]["r"][i] == pytest.approx(returns[i], rel=1e-12, abs=1e-9)
                assert info["episode"]["l"][i] == lengths[i]
                checked += 1
    assert checked >= 3, "every environment finishes an episode"
    assert undocumented(caught) == []
    # NormalizeObservation's running moments are those of every observation
    # it saw (its prior of weight 1e-4 shifts them by about 1e-7).
    raw = np.concatenate(raw)
    np.testing.assert_allclose(normalized.obs_rms.mean, raw.mean(axis=0), rtol=1e-5, atol=1e-6)
    np.testing.assert_allclose(normalized.obs_rms.var, raw.var(axis=0), rtol=1e-5, atol=1e-6)
    env.close()
    twin.close()


@pytest.mark.parametrize("mode", ["NextStep", "SameStep"])
def test_bsg_vector_env_equals_sync_vector_env_over_bsg_envs(mode):
    autoreset = gymnasium.vector.AutoresetMode(mode)
    ours = bsg.VectorEnv("SafetyBallRun-v0", 3, api="gymnasium", autoreset_mode=autoreset)
    sync = gymnasium.vector.SyncVectorEnv(
        [lambda: gymnasium.make("bsg/SafetyBallRun-v0") for _ in range(3)],
        autoreset_mode=autoreset)
    assert ours.metadata["autoreset_mode"] == sync.metadata["autoreset_mode"] == autoreset
    a, _ = ours.reset(seed=[4, None, 6])
    b, _ = sync.reset(seed=[4, None, 6])
    assert np.array_equal(a[[0, 2]], b[[0, 2]])
    a, _ = ours.reset(seed=4)
    b, _ = sync.reset(seed=4)
    assert np.array_equal(a, b)
    rng = np.random.default_rng(1)
    ended = 0
    for step in range(600):
        actions = rng.uniform(-1, 1, (3, 2))
        x, y = ours.step(actions), sync.step(actions)
        for k in range(4):
            assert np.array_equal(x[k], y[k]) and x[k].dtype == y[k].dtype, (step, k)
        assert_same_info(x[4], y[4], f"step {step}")
        ended += int((x[2] | x[3]).sum())
        if step == 300:  # a partial reset, after every environment's first end
            mask = np.array([True, False, True])
            a, _ = ours.reset(seed=[9, None, 11], options={"reset_mask": mask})
            b, _ = sync.reset(seed=[9, None, 11], options={"reset_mask": mask.copy()})
            assert np.array_equal(a, b)
    assert ended >= 5
    ours.close()
    sync.close()


def assert_same_info(x, y, where):
    assert x.keys() == y.keys(), (where, sorted(x), sorted(y))
    for name in x:
        if isinstance(x[name], dict):
            assert_same_info(x[name], y[name], f"{where}[{name!r}]")
        elif x[name].dtype == object:
            for a, b in zip(x[name], y[name]):
                assert (a is None and b is None) or np.array_equal(a, b), (where, name)
        else:
            assert x[name].dtype == y[name].dtype and np.array_equal(x[name], y[name]), \
                (where, name)


def test_vector_metadata_call_get_attr_and_render():
    vector = gymnasium.make_vec("bsg/SafetyCarCircle-v0", num_envs=2)
    assert vector.metadata["render_fps"] == 60
    assert vector.get_attr("max_episode_steps") == (500, 500)
    assert vector.call("action_space") == (vector.single_action_space,) * 2
    with pytest.raises(AttributeError, match="cannot call or read 'reset'"):
        vector.call("reset")
    if not core_renders():
        with pytest.raises(NotImplementedError, match="render_mode"):
            vector.render()
    vector.close()


def test_render_mode_rgb_array_where_the_environments_render():
    if not core_renders():
        pytest.skip("this build's environments do not render")
    env = gymnasium.make("bsg/SafetyBallCircle-v0", render_mode="rgb_array")
    env.reset(seed=0)
    frame = env.render()
    assert env.render_mode == "rgb_array"
    assert frame.ndim == 3 and frame.shape[2] == 3 and frame.dtype == np.uint8
    vector = gymnasium.make_vec("bsg/SafetyBallCircle-v0", num_envs=2, render_mode="rgb_array")
    vector.reset(seed=0)
    frames = vector.render()
    assert len(frames) == 2 and all(f.shape == frame.shape for f in frames)
    vector.close()
