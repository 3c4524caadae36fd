"""Seeds mean episodes, copies are equal and independent, and the options
gymnasium's and Safety-Gymnasium's callers pass. Oracles: a new environment
reset with the same seed (for seeded resets after any history), the original
environment stepped with the same actions (for pickle and deepcopy), the
original suite's clipping (Ball clips to [-1, 1], the Car does not), and step
counts (for max_episode_steps and autoreset)."""

import copy
import pickle
import warnings

import numpy as np
import pytest

import bsg

IDS = bsg.env_ids()


def play(env, actions):
    """Every number a step returns, for exact comparison."""
    trace = []
    for action in actions:
        obs, reward, cost, terminated, truncated, info = env.step(action)
        trace.append((obs.tolist(), reward, cost, terminated, truncated, sorted(info.items())))
    return trace


def random_actions(env, steps, seed):
    return np.random.default_rng(seed).uniform(-1, 1, (steps, env.spec.action_dim))


@pytest.mark.parametrize("env_id", IDS)
def test_seeded_reset_gives_the_same_episode_whatever_came_before(env_id):
    fresh = bsg.make(env_id)
    actions = random_actions(fresh, 60, seed=1)
    first_obs, _ = fresh.reset(seed=7)
    expected = play(fresh, actions)
    used = bsg.make(env_id)
    used.reset(seed=3)
    play(used, random_actions(used, 100, seed=2))  # motor targets, contacts, Box clock, ...
    used.reset()
    play(used, random_actions(used, 25, seed=3))
    obs, _ = used.reset(seed=7)
    assert np.array_equal(obs, first_obs)
    assert play(used, actions) == expected


def test_unseeded_resets_keep_the_history_dependent_stream():
    # reset() continues as before (training and the C++ rollouts rely on it):
    # a fresh env's reset(seed=11) then reset() differs from reset(seed=11).
    env = bsg.make("SafetyCarReach-v0")
    a, _ = env.reset(seed=11)
    b, _ = env.reset()
    assert not np.array_equal(a, b)


def history(env, seed):
    """Seeded reset, steps, an unseeded reset, more steps."""
    env.reset(seed=seed)
    play(env, random_actions(env, 40, seed))
    env.reset()
    play(env, random_actions(env, 30, seed + 1))


@pytest.mark.parametrize("env_id", IDS)
def test_pickle_and_deepcopy_step_like_the_original(env_id):
    env = bsg.make(env_id)
    history(env, seed=5)
    pickled = pickle.loads(pickle.dumps(env))
    copied = copy.deepcopy(env)
    assert pickled.spec == env.spec and copied.spec == env.spec
    actions = random_actions(env, 50, seed=9)
    expected = play(env, actions)
    assert play(pickled, actions) == expected
    assert play(copied, actions) == expected
    # Independent: stepping one copy further does not move the others.
    more = random_actions(env, 10, seed=10)
    after = play(copied, more)
    assert play(pickled, more) == after
    assert play(env, more) == after


def test_copies_of_new_and_gymnasium_api_environments():
    new = bsg.make("SafetyBallRun-v0")
    clone = copy.deepcopy(new)
    assert np.array_equal(clone.reset()[0], bsg.make("SafetyBallRun-v0").reset()[0])
    gym = bsg.make("SafetyDroneCircle-v0", api="gymnasium", max_episode_steps=30)
    gym.reset(seed=2)
    gym.step(np.zeros(4))
    twin = pickle.loads(pickle.dumps(gym))
    for action in random_actions(gym.unwrapped.env, 40, seed=4):
        a, b = gym.step(action), twin.step(action)
        assert np.array_equal(a[0], b[0]) and a[1:] == b[1:]
        if a[2] or a[3]:
            break
    assert a[3], "max_episode_steps=30 survives the copy"


def test_copy_errors_name_the_remedy():
    env = bsg.make("SafetyBallReach-v0")
    env.close()
    with pytest.raises(RuntimeError, match="closed"):
        pickle.dumps(env)
    env = bsg.make("SafetyBallReach-v0")
    env.reset(seed=0)
    zeros = np.zeros(2)
    for _ in range(100_001):  # one more than a copy replays
        if env.step(zeros)[4]:
            env.reset()
    with pytest.raises(RuntimeError,
                       match=r"100001 steps after its last seeded reset.*reset\(seed"):
        copy.deepcopy(env)
    env.reset(seed=1)
    env.step(zeros)
    assert copy.deepcopy(env).step(zeros)[0].tolist() == env.step(zeros)[0].tolist()


def test_specs_pickle():
    spec = bsg.make("SafetyAntGather-v0").spec
    clone = pickle.loads(pickle.dumps(spec))
    assert clone == spec and isinstance(clone, bsg.EnvSpec)
    assert (clone.id, clone.agent, clone.max_episode_steps, clone.cost_limit) == \
        ("SafetyAntGather-v0", "Ant", 1000, 0.2)
    assert clone.cost_term_names == ["cost_gathered_bombs", "cost_out_of_range"]


def test_out_of_range_actions_are_treated_as_the_original_and_warn_once():
    ball, clipped = bsg.make("SafetyBallRun-v0"), bsg.make("SafetyBallRun-v0")
    car, unclipped = bsg.make("SafetyCarRun-v0"), bsg.make("SafetyCarRun-v0")
    for env in (ball, clipped, car, unclipped):
        env.reset(seed=0)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        for _ in range(5):
            over = ball.step(np.array([3.0, -2.0]))
            within = clipped.step(np.array([1.0, -1.0]))
            car_over = car.step(np.array([2.0, 0.0]))
            car_within = unclipped.step(np.array([1.0, 0.0]))
    assert over[0].tolist() == within[0].tolist()          # the Ball clips
    assert car_over[0].tolist() != car_within[0].tolist()  # the Car does not
    messages = [str(w.message) for w in caught]
    assert len(messages) == 2, messages  # once per environment: ball and car
    assert "clipped to the bounds" in messages[0] and "SafetyBallRun-v0" in messages[0]
    assert "does not clip" in messages[1]


def test_max_episode_steps_autoreset_and_gymnasium_options():
    env = bsg.make("SafetyBallCircle-v0", max_episode_steps=10, disable_env_checker=True,
                   render_mode=None)
    env.reset(seed=0)
    flags = [env.step(np.zeros(2))[4] for _ in range(10)]
    assert flags == [False] * 9 + [True]
    with pytest.raises(ValueError, match="max_episode_steps must be an int >= 1"):
        bsg.make("SafetyBallCircle-v0", max_episode_steps=0)
    auto = bsg.make("SafetyBallCircle-v0", api="gymnasium", autoreset=True, max_episode_steps=3)
    oracle = bsg.make("SafetyBallCircle-v0")
    auto.reset(seed=4)
    oracle.reset(seed=4)
    for _ in range(3):
        auto.step(np.zeros(2))
        oracle.step(np.zeros(2))
    obs, reward, terminated, truncated, info = auto.step(np.ones(2))
    assert np.array_equal(obs, oracle.reset()[0])
    assert (reward, terminated, truncated, info) == (0.0, False, False, {})
