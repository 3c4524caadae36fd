"""bsg as a Gymnasium environment, checked by the real Gymnasium of each
supported version (ctest runs this file once per version: 1.x, 0.29 and 0.28,
gymnasium_import.py): gymnasium.make of every bsg/ id passes gymnasium's own
check_env; gymnasium's wrappers (CleanRL's stack among them) run full episodes
over a bsg environment without warnings and keep a spec; np_random is seeded
as gymnasium seeds it; bsg.VectorEnv(api="gymnasium") returns what the
version's own SyncVectorEnv returns over the same environments, and the
version's vector wrappers run on it. Oracles: gymnasium's checker, wrappers and
SyncVectorEnv themselves, numpy's default_rng for np_random, the test's own
sums of each episode's rewards for the episode statistics."""

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
IS_1X = int(gymnasium.__version__.split(".")[0]) >= 1
# Documented (docs/python.md#the-single-environment): check_env warns whenever it is given a
# wrapped environment, which gymnasium.make always returns; 0.29's checker also looks up
# env.seed through the wrappers, which warns for every environment (CartPole's too).
DOCUMENTED = ("is different from the unwrapped version",
              "env.seed to get variables from other wrappers is deprecated")
# gymnasium.make_vec's mode for the registered vector entry point (0.x calls it "custom").
VECTOR_ENTRY_POINT = "vector_entry_point" if IS_1X else "custom"


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
    # Under make's TimeLimit an inner autoreset would truncate every later step (0.x's
    # make takes autoreset=True itself, for its AutoResetWrapper).
    with pytest.raises(TypeError, match="gymnasium.wrappers.Autoreset"):
        gymnasium.make("bsg/SafetyBallCircle-v0", **({"autoreset": True} if IS_1X else
                                                      {"api": "safety"}))
    vector = gymnasium.make_vec("bsg/SafetyBallRun-v0", num_envs=2, box_clock="simulated",
                                **({} if IS_1X else {"vectorization_mode": "custom"}))
    assert isinstance(vector, bsg.VectorEnv) and isinstance(vector, gymnasium.vector.VectorEnv)
    assert vector.spec.id == "bsg/SafetyBallRun-v0"
    if IS_1X:  # 0.x's make_vec passes the environment's keywords to no vector entry point
        assert vector.spec.kwargs["box_clock"] == "simulated"
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


def clip_observation(env):
    """TransformObservation as CleanRL uses it (1.x also takes the new space)."""
    clip = lambda obs: np.clip(obs, -10, 10)  # noqa: E731
    if IS_1X:
        return gymnasium.wrappers.TransformObservation(env, clip, env.observation_space)
    return gymnasium.wrappers.TransformObservation(env, clip)


def cleanrl_stack(env):
    """ppo_continuous_action.py's wrappers, in its order."""
    w = gymnasium.wrappers
    env = clip_observation(w.NormalizeObservation(w.ClipAction(w.RecordEpisodeStatistics(env))))
    return w.TransformReward(w.NormalizeReward(env, gamma=0.99), lambda r: np.clip(r, -10, 10))


def rescale_action(env):
    wrapped = gymnasium.wrappers.RescaleAction(env, 0.0, 1.0)
    if wrapped.action_space.low[0] != 0.0:  # 0.28 leaves the inner space in place (0.29 fixed it)
        wrapped.action_space = gymnasium.spaces.Box(0.0, 1.0, env.action_space.shape, np.float64)
    return wrapped


WRAPPERS = {
    "TimeLimit": lambda env: gymnasium.wrappers.TimeLimit(env, 50),
    "RecordEpisodeStatistics": gymnasium.wrappers.RecordEpisodeStatistics,
    "NormalizeObservation": gymnasium.wrappers.NormalizeObservation,
    "NormalizeReward": gymnasium.wrappers.NormalizeReward,
    "ClipAction": gymnasium.wrappers.ClipAction,
    "RescaleAction": rescale_action,
    "FlattenObservation": gymnasium.wrappers.FlattenObservation,
    "TransformObservation": clip_observation,
    "TransformReward": lambda env: gymnasium.wrappers.TransformReward(env, lambda r: 2 * r),
    # 1.x resets in the next step; 0.x's AutoResetWrapper in the same step.
    "Autoreset": gymnasium.wrappers.Autoreset if IS_1X else gymnasium.wrappers.AutoResetWrapper,
    "PassiveEnvChecker": gymnasium.wrappers.PassiveEnvChecker,
    "OrderEnforcing": gymnasium.wrappers.OrderEnforcing,
    "CleanRL": cleanrl_stack,
}


@pytest.mark.parametrize("name", sorted(WRAPPERS))
@pytest.mark.parametrize("env_id", ["SafetyBallCircle-v0", "SafetyAntRun-v0"])
def test_gymnasium_wrappers_run_a_full_episode_without_warnings(name, env_id):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        env = WRAPPERS[name](bsg.make(env_id, api="gymnasium"))
        assert env.spec is not None and env.spec.id == f"bsg/{env_id}"
        obs, reward, terminated, truncated, info = episode(env)
        if name == "Autoreset" and not IS_1X:  # the ended episode's info moved to final_info
            assert "cost" in info["final_info"] and "final_observation" in info
        else:
            assert "cost" in info
        if name == "TimeLimit":
            assert truncated and env._elapsed_steps == 50
        if name == "Autoreset" and IS_1X:  # the next step resets
            obs, reward, terminated, truncated, info = env.step(env.action_space.sample())
            assert (reward, terminated, truncated) == (0.0, False, False)
        if name == "CleanRL":  # RecordEpisodeStatistics innermost: the episode's figures
            assert info["episode"]["l"] >= 1 and np.isfinite(info["episode"]["r"])
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
    # 0.x sums the returns in float32.
    assert info["episode"]["r"] == pytest.approx(total, rel=1e-12 if IS_1X else 1e-5, abs=1e-12)
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
    """bsg's vector env with gymnasium's API, or the version's own over bsg envs."""
    if kind == "bsg":
        return bsg.VectorEnv("SafetyBallRun-v0", num_envs, seed=0, api="gymnasium", **kwargs)
    if IS_1X:
        return gymnasium.make_vec("bsg/SafetyBallRun-v0", num_envs=num_envs,
                                  vectorization_mode=kind, vector_kwargs=kwargs)
    vector = {"sync": gymnasium.vector.SyncVectorEnv, "async": gymnasium.vector.AsyncVectorEnv}
    return vector[kind]([lambda: gymnasium.make("bsg/SafetyBallRun-v0")] * num_envs, **kwargs)


def vector_wrappers():
    """(NormalizeObservation, RecordEpisodeStatistics) for vector environments."""
    if IS_1X:
        return (gymnasium.wrappers.vector.NormalizeObservation,
                gymnasium.wrappers.vector.RecordEpisodeStatistics)
    return gymnasium.wrappers.NormalizeObservation, gymnasium.wrappers.RecordEpisodeStatistics


@pytest.mark.parametrize("kind", ["bsg", "sync", "async"])
def test_vector_wrappers_statistics_equal_the_episodes_own_sums(kind):
    normalize, record = vector_wrappers()
    normalized = normalize(make_vector(kind, 3))
    env = record(normalized)
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
            if IS_1X:  # next-step autoreset: the step after an episode's end is a reset
                returns[pending], lengths[pending] = 0.0, 0
                returns[~pending] += reward[~pending]
                lengths[~pending] += 1
            else:  # same-step autoreset: every step belongs to an episode
                returns += reward
                lengths += 1
            pending = terminated | truncated
            for i in np.flatnonzero(info.get("_episode", np.zeros(3, bool))):
                assert info["episode"]["r"][i] == pytest.approx(
                    returns[i], rel=1e-12 if IS_1X else 1e-5, abs=1e-9)  # 0.x sums in float32
                assert info["episode"]["l"][i] == lengths[i]
                checked += 1
            if not IS_1X:
                returns[pending], lengths[pending] = 0.0, 0
    assert checked >= 3, "every environment finishes an episode"
    assert undocumented(caught) == []
    # NormalizeObservation's running moments are those of every observation
    # it saw (its prior of weight 1e-4 shifts them by about 1e-7).
    raw = np.concatenate(raw)
    np.testing.assert_allclose(normalized.obs_rms.mean, raw.mean(axis=0), rtol=1e-5, atol=1e-6)
    np.testing.assert_allclose(normalized.obs_rms.var, raw.var(axis=0), rtol=1e-5, atol=1e-6)
    env.close()
    twin.close()


MODES = ["NextStep", "SameStep"] if IS_1X else ["SameStep"]


@pytest.mark.parametrize("mode", MODES)
def test_bsg_vector_env_equals_sync_vector_env_over_bsg_envs(mode):
    if IS_1X:
        autoreset = gymnasium.vector.AutoresetMode(mode)
        ours = bsg.VectorEnv("SafetyBallRun-v0", 3, api="gymnasium", autoreset_mode=autoreset)
        sync = gymnasium.vector.SyncVectorEnv(
            [lambda: gymnasium.make("bsg/SafetyBallRun-v0") for _ in range(3)],
            autoreset_mode=autoreset)
        assert ours.metadata["autoreset_mode"] == sync.metadata["autoreset_mode"] == autoreset
    else:  # 0.x's only mode, bsg's default there
        ours = bsg.VectorEnv("SafetyBallRun-v0", 3, api="gymnasium")
        sync = gymnasium.vector.SyncVectorEnv(
            [lambda: gymnasium.make("bsg/SafetyBallRun-v0") for _ in range(3)])
        assert ours.metadata["autoreset_mode"] == ours.autoreset_mode == "SameStep"
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
        if step == 300 and IS_1X:  # a partial reset (1.x), after every environment's first end
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
                if isinstance(a, dict):  # 0.x's final_info: each ended environment's info
                    assert isinstance(b, dict), (where, name)
                    assert_same_info({k: np.asarray(v) for k, v in a.items()},
                                     {k: np.asarray(v) for k, v in b.items()}, where)
                else:
                    assert (a is None and b is None) or np.array_equal(a, b), (where, name)
        else:
            assert x[name].dtype == y[name].dtype and np.array_equal(x[name], y[name]), \
                (where, name)


def test_vector_env_claims_what_it_is():
    safety = bsg.VectorEnv("SafetyBallRun-v0", 2, seed=0)
    gym = bsg.VectorEnv("SafetyBallRun-v0", 2, seed=0, api="gymnasium")
    # bsg's own API (6-tuple) claims no gymnasium class; gymnasium's API is one.
    assert isinstance(safety, bsg.VectorEnv) and not isinstance(safety, gymnasium.vector.VectorEnv)
    assert isinstance(gym, bsg.GymnasiumVectorEnv) and isinstance(gym, bsg.VectorEnv)
    assert isinstance(gym, gymnasium.vector.VectorEnv)
    safety.reset(seed=0)
    gym.reset(seed=0)
    actions = np.zeros((2, 2))
    assert len(safety.step(actions)) == 6 and len(gym.step(actions)) == 5
    # autoreset_mode says what each does: four steps with a 3-step limit.
    for mode, expected in ((None, "NextStep" if IS_1X else "SameStep"), ("SameStep", "SameStep")):
        vector = bsg.VectorEnv("SafetyBallRun-v0", 1, api="gymnasium", autoreset_mode=mode,
                               max_episode_steps=3)
        assert str(getattr(vector.autoreset_mode, "value", vector.autoreset_mode)) == expected
        assert vector.metadata["autoreset_mode"] == vector.autoreset_mode
        first, _ = vector.reset(seed=2)
        rows = [vector.step(np.ones((1, 2))) for _ in range(4)]  # full speed: rewards not 0
        assert rows[2][3][0]  # truncated at the third step
        if expected == "NextStep":  # the fourth step is the reset: reward 0, the first obs again
            assert rows[3][1][0] == 0.0 and not rows[3][3][0]
        else:  # the third step's row already holds the next episode's first observation
            key = "final_obs" if IS_1X else "final_observation"
            assert rows[2][4][f"_{key}"][0] and rows[2][4][key][0].shape == first[0].shape
            assert rows[3][1][0] != 0.0
        vector.close()
    if not IS_1X:
        with pytest.raises(ValueError, match="needs Gymnasium 1.x"):
            bsg.VectorEnv("SafetyBallRun-v0", 1, api="gymnasium", autoreset_mode="NextStep")
    safety.close()
    gym.close()


def test_a_vector_wrapper_over_the_default_vector_env():
    """The default bsg.VectorEnv (6-tuple) is refused where gymnasium checks the class
    (1.x's vector wrappers, at construction); the documented api="gymnasium" runs."""
    normalize, record = vector_wrappers()
    if IS_1X:
        with pytest.raises(TypeError, match="gymnasium.vector.VectorEnv"):
            record(bsg.VectorEnv("SafetyBallRun-v0", 4, seed=0))
    env = record(bsg.VectorEnv("SafetyBallRun-v0", 4, seed=0, api="gymnasium"))
    env.reset(seed=0)
    rng = np.random.default_rng(3)
    finished = 0
    for _ in range(260):
        obs, reward, terminated, truncated, info = env.step(rng.uniform(-1, 1, (4, 2)))
        finished += int(info.get("_episode", np.zeros(4, bool)).sum())
    assert finished == 4  # every environment's first episode, 250 steps each
    env.close()


def test_autoreset_option_of_make_resets_in_the_next_step_under_every_version():
    env = bsg.make("SafetyBallRun-v0", api="gymnasium", autoreset=True, max_episode_steps=3)
    env.reset(seed=0)
    flags = [env.step(np.zeros(2))[1:4] for _ in range(4)]
    assert [f[2] for f in flags] == [False, False, True, False]
    assert flags[3][0] == 0.0


def test_vector_metadata_call_get_attr_and_render():
    vector = gymnasium.make_vec("bsg/SafetyCarCircle-v0", num_envs=2,
                                vectorization_mode=VECTOR_ENTRY_POINT)
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
    # 0.x's make_vec gives its vector entry point vector_kwargs only.
    options = {"render_mode": "rgb_array"}
    vector = gymnasium.make_vec("bsg/SafetyBallCircle-v0", num_envs=2,
                                vectorization_mode=VECTOR_ENTRY_POINT,
                                **(options if IS_1X else {"vector_kwargs": options}))
    vector.reset(seed=0)
    frames = vector.render()
    assert len(frames) == 2 and all(f.shape == frame.shape for f in frames)
    vector.close()
