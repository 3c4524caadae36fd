"""bsg.parallel_env: the multi-agent environments through PettingZoo's Parallel API
(docs/multi_agent.md). PettingZoo's own parallel_api_test and parallel_seed_test on
every id (PettingZoo installed, else its core in shared/pydeps beside the repository;
skipped where neither is); the split Ant against the single-agent bsg.make Ant (its
step bit for bit); the team's episode end; one-line errors for bad input."""

import numpy as np
import pytest

import gymnasium_import

PETTINGZOO = gymnasium_import.import_pettingzoo()  # before bsg: its spaces are then gymnasium's

import bsg  # noqa: E402
from pettingzoo.test import parallel_api_test, parallel_seed_test  # noqa: E402

IDS = ["SafetyAntCircle2x4-v0", "SafetyAntCircle4x2-v0", "SafetyAntRun2x4-v0", "SafetyAntRun4x2-v0",
       "SafetyBallCircle2-v0", "SafetyBallCircle3-v0", "SafetyBallReach2-v0", "SafetyCarCircle2-v0",
       "SafetyCarReach2-v0"]


def test_ids_are_listed():
    assert bsg.parallel_env_ids() == IDS
    assert not set(IDS) & set(bsg.env_ids())


@pytest.mark.parametrize("env_id", IDS)
def test_pettingzoo_parallel_api(env_id, capsys):
    parallel_api_test(bsg.parallel_env(env_id), num_cycles=120)
    assert "Passed Parallel API test" in capsys.readouterr().out


@pytest.mark.parametrize("env_id", ["SafetyBallCircle2-v0", "SafetyBallReach2-v0", "SafetyAntRun2x4-v0"])
def test_pettingzoo_parallel_seed(env_id):
    parallel_seed_test(lambda: bsg.parallel_env(env_id), num_cycles=30)


def test_split_ant_steps_as_the_single_agent_ant():
    team = bsg.parallel_env("SafetyAntRun2x4-v0")
    single = bsg.make("SafetyAntRun-v0")
    observations, _ = team.reset(seed=4)
    alone, _ = single.reset(seed=4)
    # agent_0: the body (entries 0..12), legs 0 and 1 (13..20), feet 0 and 1 (29, 30).
    expected = np.concatenate([alone[0:13], alone[13:21], alone[29:31]])
    assert np.array_equal(observations["agent_0"], expected)
    rng = np.random.default_rng(0)
    for _ in range(80):
        action = rng.uniform(-1, 1, 8)
        observations, rewards, terminations, truncations, infos = team.step(
            {"agent_0": action[:4], "agent_1": action[4:]})
        alone, reward, cost, terminated, truncated, info = single.step(action)
        assert np.array_equal(team.state(), alone)
        assert np.array_equal(observations["agent_1"],
                              np.concatenate([alone[0:13], alone[21:29], alone[31:33]]))
        for agent in team.possible_agents:
            assert rewards[agent] == reward and infos[agent]["cost"] == cost
            assert infos[agent]["cost_velocity_violation"] == info["cost_velocity_violation"]
            assert terminations[agent] == terminated and truncations[agent] == truncated
        if terminated or truncated:
            break


def test_the_team_ends_together_and_agents_empty():
    env = bsg.parallel_env("SafetyBallCircle2-v0", max_episode_steps=3)
    env.reset(seed=0)
    zero = {agent: np.zeros(2) for agent in env.agents}
    for _ in range(2):
        _, _, terminations, truncations, _ = env.step(zero)
        assert not any(truncations.values()) and env.agents == ["agent_0", "agent_1"]
    _, _, terminations, truncations, _ = env.step(zero)
    assert all(truncations.values()) and not any(terminations.values()) and env.agents == []
    with pytest.raises(RuntimeError, match="call reset"):
        env.step(zero)


def test_state_is_every_balls_own_observation():
    env = bsg.parallel_env("SafetyBallCircle2-v0")
    observations, _ = env.reset(seed=1)
    # Each Ball's own 7 + Circle's 1 entries, then the other Ball's offset (2).
    assert env.observation_space("agent_0").shape == (10,) and env.state_space.shape == (16,)
    assert np.array_equal(env.state(), np.concatenate([observations["agent_0"][:8],
                                                       observations["agent_1"][:8]]))
    assert np.allclose(observations["agent_0"][8:10], -observations["agent_1"][8:10], rtol=0, atol=1e-15)


def test_bad_input_is_refused_with_one_line():
    with pytest.raises(ValueError, match="unknown multi-agent environment id 'SafetyBallCircle-v0'"):
        bsg.parallel_env("SafetyBallCircle-v0")
    with pytest.raises(ValueError, match=r"bodies=0: must be in \[1, 8\]"):
        bsg.parallel_env("SafetyBallCircle2-v0", bodies=0)
    with pytest.raises(ValueError, match="partition=2x4: splits the Ant's legs"):
        bsg.parallel_env("SafetyBallCircle2-v0", partition="2x4")
    env = bsg.parallel_env("SafetyBallCircle2-v0")
    env.reset(seed=0)
    with pytest.raises(ValueError, match=r"missing \['agent_1'\]"):
        env.step({"agent_0": np.zeros(2)})
    with pytest.raises(ValueError):
        env.step({"agent_0": np.zeros(3), "agent_1": np.zeros(2)})
    with pytest.raises(KeyError, match="no agent 'agent_7'"):
        env.action_space("agent_7")


def test_render_draws_every_ball():
    env = bsg.parallel_env("SafetyBallCircle2-v0", render_mode="rgb_array", width=96, height=72)
    env.reset(seed=0)
    try:
        frame = env.render()
    except RuntimeError as error:
        if "EGL" in str(error):
            pytest.skip(f"no EGL driver on this machine: {error}")
        raise
    assert frame.shape == (72, 96, 3) and frame.dtype == np.uint8
