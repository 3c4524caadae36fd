"""bsg.parallel_vector_env (docs/multi_agent.md#vectorised-multi-agent-environments) against
its oracle, N bsg.parallel_env copies played by hand: copy i reset with seed + i, stepped with
its rows of the actions and reset (continuing its stream) when the team's episode ends, gives
bit for bit the vector's observations, rewards, costs, cost terms, flags, final observations
and states; shapes and dtypes; one-line ValueErrors for bad input."""

import numpy as np
import pytest

import bsg


def random_actions(env, rng):
    return {agent: rng.uniform(-1, 1, (env.num_envs, dim))
            for agent, dim in zip(env.possible_agents, env.bsg_spec.action_dims)}


@pytest.mark.parametrize("env_id, num_threads", [("SafetyBallCircle2-v0", 2),
                                                 ("SafetyAntRun4x2-v0", 1)])
def test_environment_i_is_a_parallel_env_reset_with_seed_plus_i(env_id, num_threads):
    num_envs, seed, steps = 3, 11, 12
    vector = bsg.parallel_vector_env(env_id, num_envs, num_threads=num_threads, max_episode_steps=5)
    singles = [bsg.parallel_env(env_id, max_episode_steps=5) for _ in range(num_envs)]
    observations, _ = vector.reset(seed=seed)
    expected = [single.reset(seed=seed + i)[0] for i, single in enumerate(singles)]
    agents = vector.possible_agents
    for agent in agents:
        assert np.array_equal(observations[agent], np.stack([e[agent] for e in expected]))
    assert np.array_equal(vector.state(), np.stack([single.state() for single in singles]))
    rng = np.random.default_rng(0)
    ends = 0
    for _ in range(steps):
        actions = random_actions(vector, rng)
        observations, rewards, costs, terminations, truncations, infos = vector.step(actions)
        for i, single in enumerate(singles):
            obs, rew, term, trunc, info = single.step({a: actions[a][i] for a in agents})
            final_state = single.state()
            for agent in agents:
                assert np.array_equal(infos[agent]["final_observation"][i], obs[agent])
                assert rewards[agent][i] == rew[agent]
                assert costs[agent][i] == info[agent]["cost"]
                for name in vector.bsg_spec.cost_term_names:
                    assert infos[agent][name][i] == info[agent][name]
                assert terminations[agent][i] == term[agent]
                assert truncations[agent][i] == trunc[agent]
                assert infos[agent]["_final_observation"][i] == (term[agent] or trunc[agent])
            assert np.array_equal(vector.final_state()[i], final_state)
            if term[agents[0]] or trunc[agents[0]]:
                ends += 1
                obs, _ = single.reset()  # continues the stream, as the vector's auto-reset
            for agent in agents:
                assert np.array_equal(observations[agent][i], obs[agent])
            assert np.array_equal(vector.state()[i], single.state())
    assert ends == 2 * num_envs  # truncations after steps 5 and 10: the test crosses auto-resets


def test_shapes_and_dtypes():
    vector = bsg.parallel_vector_env("SafetyBallCircle3-v0", 4, num_threads=2)
    observations, infos = vector.reset(seed=0)
    assert vector.possible_agents == ["agent_0", "agent_1", "agent_2"] and set(infos) == set(observations)
    # docs/multi_agent.md#ids: 12 observation entries and 2 actions per agent, a state of 24.
    for agent in vector.possible_agents:
        assert observations[agent].shape == (4, 12) and observations[agent].dtype == np.float64
        assert vector.observation_space(agent).shape == (4, 12)
        assert vector.single_action_spaces[agent].shape == (2,)
    assert vector.state().shape == (4, 24) and vector.state_space.shape == (4, 24)
    observations, rewards, costs, terminations, truncations, infos = vector.step(
        random_actions(vector, np.random.default_rng(1)))
    for agent in vector.possible_agents:
        assert rewards[agent].shape == (4,) and rewards[agent].dtype == np.float64
        assert costs[agent].shape == (4,) and costs[agent].dtype == np.float64
        assert terminations[agent].dtype == np.bool_ and truncations[agent].shape == (4,)
        assert infos[agent]["final_observation"].shape == (4, 12)
        assert infos[agent]["cost_agent_collisions"].shape == (4,)
    assert vector.stack(observations).shape == (4, 3, 12)


def test_stacked_actions_equal_the_dict_of_actions_and_threads_change_nothing():
    one = bsg.parallel_vector_env("SafetyCarCircle2-v0", 3, num_threads=1)
    two = bsg.parallel_vector_env("SafetyCarCircle2-v0", 3, num_threads=2)
    one.reset(seed=3)
    two.reset(seed=3)
    rng = np.random.default_rng(2)
    for _ in range(10):
        actions = random_actions(one, rng)
        a = one.step(actions)
        b = two.step(np.stack([actions["agent_0"], actions["agent_1"]], axis=1))
        for x, y in zip(a[:5], b[:5]):
            for agent in one.possible_agents:
                assert np.array_equal(x[agent], y[agent])
    assert np.array_equal(one.state(), two.state())


def test_a_seeded_reset_is_a_fresh_start_and_reset_without_seed_starts_from_the_constructors():
    played = bsg.parallel_vector_env("SafetyCarCircle2-v0", 2, num_threads=2, seed=4)
    first, _ = played.reset()
    fresh = bsg.parallel_vector_env("SafetyCarCircle2-v0", 2, num_threads=1)
    expected, _ = fresh.reset(seed=4)
    assert np.array_equal(first["agent_1"], expected["agent_1"])
    full = {agent: np.full((2, 2), 0.9) for agent in played.possible_agents}
    for _ in range(20):
        played.step(full)
    again, _ = played.reset(seed=4)
    assert np.array_equal(again["agent_0"], expected["agent_0"])
    assert np.array_equal(played.state(), fresh.state())
    played.step(full)
    fresh.step(full)
    assert np.array_equal(played.state(), fresh.state())


def one_line_value_error(call, *words):
    with pytest.raises(ValueError) as error:
        call()
    message = str(error.value)
    assert "\n" not in message
    for word in words:
        assert word in message, message


def test_bad_input_raises_value_error_naming_the_problem():
    one_line_value_error(lambda: bsg.parallel_vector_env("SafetyBallCircle-v0", 2),
                         "unknown multi-agent environment id", "SafetyBallCircle2-v0")
    one_line_value_error(lambda: bsg.parallel_vector_env("SafetyBallCircle2-v0", 0), "num_envs must be >= 1")
    one_line_value_error(lambda: bsg.parallel_vector_env("SafetyBallCircle2-v0", 2, num_threads=-1),
                         "num_threads must be >= 0")
    one_line_value_error(lambda: bsg.parallel_vector_env("SafetyBallCircle2-v0", 2, bodies=0), "bodies")
    vector = bsg.parallel_vector_env("SafetyBallCircle2-v0", 2, num_threads=2)
    vector.reset(seed=0)
    zeros = {agent: np.zeros((2, 2)) for agent in vector.possible_agents}
    one_line_value_error(lambda: vector.step({"agent_0": zeros["agent_0"]}), "missing ['agent_1']")
    one_line_value_error(lambda: vector.step({**zeros, "agent_1": np.zeros((2, 3))}),
                         "agent_1's action has shape (2, 3)", "(2, 2)")
    one_line_value_error(lambda: vector.step(np.zeros((2, 2))), "(2, 2, 2)", "got shape (2, 2)")
    bad = {**zeros, "agent_1": np.array([[0.0, 0.0], [0.0, np.nan]])}
    one_line_value_error(lambda: vector.step(bad), "environment 1", "agent_1's action entry 1 is not finite")
    one_line_value_error(lambda: vector.stack({"agent_0": np.zeros((2, 3)), "agent_1": np.zeros((2, 4))}),
                         "differ in shape")
    vector.close()
    with pytest.raises(RuntimeError, match="closed"):
        vector.step(zeros)
