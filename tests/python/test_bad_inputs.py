"""Every bad input gives a clear Python error naming the problem, and the
environment is left as it was (the oracle for "unchanged": a twin environment
that never saw the bad input)."""

import numpy as np
import pytest

import bsg


@pytest.fixture
def env():
    env = bsg.make("SafetyBallCircle-v0")
    env.reset(seed=0)
    return env


@pytest.mark.parametrize("action", [
    np.zeros(3), np.zeros((1, 2)), np.zeros(()), [0.0], [[0.0, 0.0]], 0.5,
])
def test_wrong_shape_names_the_expected_shape(env, action):
    with pytest.raises(ValueError, match=r"expected a float array of shape \(2,\)"):
        env.step(action)


@pytest.mark.parametrize("action", [
    np.zeros(2, dtype=bool), np.zeros(2, dtype=complex), np.array(["a", "b"]),
    np.array([object(), object()]), [0.0, "x"], None, {"a": 1},
])
def test_wrong_dtype_names_the_expected_shape(env, action):
    with pytest.raises(ValueError, match=r"expected a float array of shape \(2,\)"):
        env.step(action)


@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf])
def test_non_finite_action_is_rejected_and_nothing_steps(env, bad):
    twin = bsg.make("SafetyBallCircle-v0")
    twin.reset(seed=0)
    with pytest.raises(ValueError, match=r"not finite.*shape \(2,\)"):
        env.step(np.array([0.1, bad]))
    assert np.array_equal(env.step(np.full(2, 0.3))[0], twin.step(np.full(2, 0.3))[0])


@pytest.mark.parametrize("action", [
    [0.5, -0.25], (0.5, -0.25), np.array([0.5, -0.25], dtype=np.float32),
    np.array([[0.5, 9.0], [-0.25, 9.0]])[:, 0],  # a non-contiguous view
    np.array([1, 0]),  # integers, as gymnasium's float64 Box accepts them
])
def test_accepted_action_forms_step_like_a_float64_array(env, action):
    twin = bsg.make("SafetyBallCircle-v0")
    twin.reset(seed=0)
    expected = twin.step(np.asarray(action, dtype=np.float64))
    result = env.step(action)
    assert np.array_equal(result[0], expected[0]) and result[1] == expected[1]


def test_unknown_id_lists_the_valid_ids():
    with pytest.raises(ValueError, match="SafetyBallCircle-v0.*SafetyDroneRun-v0"):
        bsg.make("SafetyBallCircle-v1")
    with pytest.raises(ValueError, match="valid ids"):
        bsg.VectorEnv("NoSuchEnv", 2)
    with pytest.raises(TypeError, match="env_id must be a str"):
        bsg.make(3)


def test_closed_env_raises_a_clear_error():
    env = bsg.make("SafetyBallCircle-v0")
    env.reset(seed=0)
    env.close()
    env.close()  # closing twice is allowed
    assert env.closed
    with pytest.raises(RuntimeError, match=r"step\(\) called on a closed environment"):
        env.step(np.zeros(2))
    with pytest.raises(RuntimeError, match=r"reset\(\) called on a closed environment"):
        env.reset()
    vector = bsg.VectorEnv("SafetyBallCircle-v0", 2)
    vector.close()
    with pytest.raises(RuntimeError, match="closed"):
        vector.step(np.zeros((2, 2)))


def test_step_before_reset_raises():
    with pytest.raises(RuntimeError, match=r"before reset\(\)"):
        bsg.make("SafetyBallCircle-v0").step(np.zeros(2))
    with pytest.raises(RuntimeError, match=r"before reset\(\)"):
        bsg.VectorEnv("SafetyBallCircle-v0", 2).step(np.zeros((2, 2)))


@pytest.mark.parametrize("seed,error", [(-1, ValueError), (2**64, ValueError),
                                        (1.5, TypeError), (True, TypeError), ("3", TypeError)])
def test_bad_seed(env, seed, error):
    with pytest.raises(error, match="seed"):
        env.reset(seed=seed)


def test_numpy_integer_seed_is_accepted(env):
    assert np.array_equal(env.reset(seed=np.int64(4))[0], env.reset(seed=4)[0])


def test_bad_options():
    # Keywords other than the options are environment parameters.
    with pytest.raises(ValueError, match="max_episode_step=10: unknown parameter.*max_episode_steps"):
        bsg.make("SafetyBallCircle-v0", max_episode_step=10)
    with pytest.raises(ValueError, match="box_clock must be"):
        bsg.make("SafetyBallCircle-v0", box_clock="wall")
    with pytest.raises(ValueError, match="api must be"):
        bsg.make("SafetyBallCircle-v0", api="gym")
    with pytest.raises(ValueError, match="takes no options"):
        bsg.make("SafetyBallCircle-v0").reset(options={"x": 1})


def test_bad_vector_arguments_and_actions():
    with pytest.raises(ValueError, match="num_envs must be >= 1"):
        bsg.VectorEnv("SafetyBallCircle-v0", 0)
    with pytest.raises(ValueError, match="num_threads must be >= 0"):
        bsg.VectorEnv("SafetyBallCircle-v0", 2, num_threads=-1)
    vector = bsg.VectorEnv("SafetyBallCircle-v0", 3, num_threads=2)
    vector.reset()
    with pytest.raises(ValueError, match=r"shape \(3, 2\)"):
        vector.step(np.zeros(6))
    with pytest.raises(ValueError, match=r"shape \(3, 2\)"):
        vector.step(np.zeros((2, 2)))
    actions = np.zeros((3, 2))
    actions[2, 1] = np.nan
    with pytest.raises(ValueError, match=r"\[2, 1\] is not finite.*shape \(3, 2\)"):
        vector.step(actions)


@pytest.mark.parametrize("make", [lambda: bsg.Env("SafetyBallGather-v0", bombs=-1),
                                  lambda: bsg.VectorEnv("SafetyBallGather-v0", 2, bombs=-1)])
def test_an_object_whose_constructor_raised_prints_safely(make):
    # A traceback printer (pytest's, a debugger's) calls repr() on `self` of the
    # failed __init__, whose C++ object was never built.
    with pytest.raises(ValueError, match="bombs=-1") as raised:
        make()
    frame = raised.tb
    while frame.tb_next is not None:
        frame = frame.tb_next
    half_made = frame.tb_frame.f_locals["self"]
    assert repr(half_made).endswith("(not constructed)>")
