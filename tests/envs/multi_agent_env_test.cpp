// The multi-agent environments (envs/multi_agent_env.h, docs/multi_agent.md):
// the split Ant against the single-agent Ant (its step bit for bit, the
// observation slices from hand-written index lists), the collision cost of two
// Balls on a scripted head-on encounter against the hand-computed step of
// contact, the spawn rule over many seeds, determinism from a seed, and
// one-line refusals of bad ids and descriptions.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/random.h"
#include "envs/env.h"
#include "envs/multi_agent_env.h"

namespace bsg::envs {
namespace {
// Its own names apart from the other files of its test batch (tests/CMakeLists.txt).
namespace multi_agent_env_test {

using Indices = std::vector<int>;

Indices range(int first, int last) {  // [first, last]
  Indices out(static_cast<size_t>(last - first + 1));
  std::iota(out.begin(), out.end(), first);
  return out;
}

Indices join(std::initializer_list<Indices> parts) {
  Indices out;
  for (const Indices& part : parts) out.insert(out.end(), part.begin(), part.end());
  return out;
}

// The Ant's observation (docs/environments.md#ant): 0..12 the body (0.1·p,
// 0.3·v, quaternion, 0.15·ω), 13..28 two entries per joint (hip_1, ankle_1,
// hip_2, ..., ankle_4: legs front_left, front_right, left_back, right_back),
// 29..32 the feet, then the task's entries (Circle: 33).
const Indices kBody = range(0, 12);
Indices leg(int l) { return range(13 + 4 * l, 16 + 4 * l); }
Indices foot(int l) { return {29 + l}; }

struct SplitCase {
  std::string multi_id;
  std::string single_id;
  std::vector<Indices> observed;      // per agent, indices into the single observation
  std::vector<Indices> action_joints;  // per agent, the joints its entries drive
};

std::vector<SplitCase> split_cases() {
  const Indices circle_task = {33};
  return {
      {"SafetyAntRun2x4-v0", "SafetyAntRun-v0",
       {join({kBody, leg(0), leg(1), foot(0), foot(1)}), join({kBody, leg(2), leg(3), foot(2), foot(3)})},
       {range(0, 3), range(4, 7)}},
      {"SafetyAntRun4x2-v0", "SafetyAntRun-v0",
       {join({kBody, leg(0), foot(0)}), join({kBody, leg(1), foot(1)}), join({kBody, leg(2), foot(2)}),
        join({kBody, leg(3), foot(3)})},
       {range(0, 1), range(2, 3), range(4, 5), range(6, 7)}},
      {"SafetyAntCircle2x4-v0", "SafetyAntCircle-v0",
       {join({kBody, leg(0), leg(1), foot(0), foot(1), circle_task}),
        join({kBody, leg(2), leg(3), foot(2), foot(3), circle_task})},
       {range(0, 3), range(4, 7)}},
  };
}

void expect_slices(const std::vector<Indices>& observed, std::span<const std::span<const double>> agents,
                   std::span<const double> single, int step) {
  ASSERT_EQ(agents.size(), observed.size());
  for (size_t k = 0; k < observed.size(); ++k) {
    ASSERT_EQ(agents[k].size(), observed[k].size()) << "agent " << k;
    for (size_t i = 0; i < observed[k].size(); ++i) {
      // Bit for bit: the same doubles, not close ones.
      ASSERT_EQ(agents[k][i], single[static_cast<size_t>(observed[k][i])])
          << "step " << step << " agent " << k << " entry " << i;
    }
  }
}

TEST(MultiAgentEnvSplitAnt, ReproducesTheSingleAgentAntBitForBit) {
  for (const SplitCase& c : split_cases()) {
    SCOPED_TRACE(c.multi_id);
    auto split = make_multi_agent(c.multi_id);
    auto single = make(c.single_id);
    const MultiAgentSpec& spec = split->spec();
    ASSERT_EQ(spec.agent_count(), static_cast<int>(c.observed.size()));
    EXPECT_EQ(spec.state_dim, single->spec().observation_dim);
    EXPECT_TRUE(spec.team_reward && spec.team_cost);
    expect_slices(c.observed, split->reset(11), single->reset(11), 0);
    Rng rng(5);
    std::vector<double> joint_action(8);
    std::vector<std::vector<double>> agent_actions(c.action_joints.size());
    int steps = 0;
    for (bool ended = false; !ended && steps < 300; ++steps) {
      // Actions beyond [-1, 1] too: the clipping must be the single agent's.
      for (double& a : joint_action) a = uniform(rng, -1.3, 1.3);
      for (size_t k = 0; k < c.action_joints.size(); ++k) {
        agent_actions[k].clear();
        for (const int joint : c.action_joints[k]) agent_actions[k].push_back(joint_action[static_cast<size_t>(joint)]);
      }
      const std::vector<std::span<const double>> actions(agent_actions.begin(), agent_actions.end());
      const MultiAgentStepResult team = split->step(actions);
      const StepResult alone = single->step(joint_action);
      expect_slices(c.observed, team.observations, alone.observation, steps + 1);
      const std::span<const double> state = split->global_state();
      ASSERT_TRUE(std::equal(state.begin(), state.end(), alone.observation.begin(), alone.observation.end()));
      for (size_t k = 0; k < c.observed.size(); ++k) {
        ASSERT_EQ(team.rewards[k], alone.reward);
        ASSERT_EQ(team.costs[k], alone.cost);
        ASSERT_EQ(team.cost_terms[k].size(), alone.cost_terms.size());
        for (size_t t = 0; t < alone.cost_terms.size(); ++t) {
          ASSERT_EQ(team.cost_terms[k][t].name, alone.cost_terms[t].name);
          ASSERT_EQ(team.cost_terms[k][t].value, alone.cost_terms[t].value);
        }
      }
      ASSERT_EQ(team.terminated, alone.terminated);
      ASSERT_EQ(team.truncated, alone.truncated);
      ended = alone.terminated || alone.truncated;
    }
    EXPECT_GT(steps, 50);  // the comparison covered a real stretch of an episode
  }
}

// Two Balls at rest, centres 1.3 m apart on the x axis (0.3 m between their
// surfaces), pushed head-on with full force. Rolling without slipping, a Ball
// accelerates at a = F/(m + I/r²) = 3.5/(0.3·7/5) = 8.33 m/s² (rolling friction
// 0.03 takes at most ~5 %: a ≥ 7.9). Bullet's semi-implicit Euler over
// h = 1/240 s sub-steps puts a Ball at x_n = a·h²·n(n+1)/2 after n of them; a
// contact is found in sub-step n+1 from x_n, once x_n ≥ 0.15 m: n(n+1) ≥
// 0.3/(a·h²) = 2074 (a = 8.33) or 2187 (a = 7.9), so n = 46 or 47, found in
// sub-step 47 or 48: both in environment step 12 (sub-steps 45..48).
constexpr int kContactStep = 12;

std::vector<Layout> head_on_layout() {
  Layout left, right;
  left.agent_position = {-0.65, 0, 0.5};
  right.agent_position = {0.65, 0, 0.5};
  return {left, right};
}

struct Encounter {
  std::vector<double> costs_agent0, costs_agent1, collision_terms0, collision_terms1, centre_distance;
};

Encounter push_head_on(MultiAgentEnv& env, int steps) {
  const std::vector<Layout> layouts = head_on_layout();
  env.reset_to(layouts);
  const std::vector<double> push_right = {1, 0}, push_left = {-1, 0};
  const std::vector<std::span<const double>> actions = {push_right, push_left};
  Encounter out;
  for (int step = 1; step <= steps; ++step) {
    const MultiAgentStepResult result = env.step(actions);
    out.costs_agent0.push_back(result.costs[0]);
    out.costs_agent1.push_back(result.costs[1]);
    out.collision_terms0.push_back(result.cost_terms[0].back().value);
    out.collision_terms1.push_back(result.cost_terms[1].back().value);
    const std::vector<EnvState> states = env.body_states();
    out.centre_distance.push_back(std::hypot(states[0].agent_position[0] - states[1].agent_position[0],
                                             states[0].agent_position[1] - states[1].agent_position[1]));
  }
  return out;
}

TEST(MultiAgentEnvBalls, CollisionCostStartsAtTheHandComputedStep) {
  auto env = make_multi_agent("SafetyBallCircle2-v0");
  ASSERT_EQ(env->spec().cost_term_names.back(), "cost_agent_collisions");
  const Encounter e = push_head_on(*env, kContactStep);
  for (int step = 1; step < kContactStep; ++step) {
    EXPECT_EQ(e.costs_agent0[step - 1], 0) << "step " << step;
    EXPECT_EQ(e.costs_agent1[step - 1], 0) << "step " << step;
    EXPECT_GT(e.centre_distance[step - 1], 1.0) << "step " << step;  // two radii of 0.5 m
  }
  EXPECT_EQ(e.costs_agent0[kContactStep - 1], 1);
  EXPECT_EQ(e.costs_agent1[kContactStep - 1], 1);
  EXPECT_EQ(e.collision_terms0[kContactStep - 1], 1);
  EXPECT_EQ(e.collision_terms1[kContactStep - 1], 1);
  // Both within |x| ≤ 6: the collision is the only cost.
  EXPECT_EQ(env->spec().cost_term_names.front(), "cost_outside_bounds");
}

TEST(MultiAgentEnvBalls, UncountedCollisionsAreReportedButCostNothingAndTeamCostsAdd) {
  auto uncounted = make_multi_agent(describe_multi_agent("SafetyBallCircle2-v0", {{"count_agent_collisions", "false"}}));
  const Encounter e = push_head_on(*uncounted, kContactStep);
  EXPECT_EQ(e.collision_terms0[kContactStep - 1], 1);
  EXPECT_EQ(e.costs_agent0[kContactStep - 1], 0);
  auto team = make_multi_agent(describe_multi_agent("SafetyBallCircle2-v0", {{"cost", "team"}}));
  const Encounter t = push_head_on(*team, kContactStep);
  EXPECT_EQ(t.costs_agent0[kContactStep - 1], 2);  // each Ball's cost 1, summed
  EXPECT_EQ(t.costs_agent1[kContactStep - 1], 2);
}

TEST(MultiAgentEnvBalls, TeamRewardIsTheSumOfTheBallsOwnRewards) {
  auto own = make_multi_agent("SafetyBallCircle3-v0");
  auto team = make_multi_agent(describe_multi_agent("SafetyBallCircle3-v0", {{"reward", "team"}}));
  own->reset(2);
  team->reset(2);
  const std::vector<double> a0 = {0.5, -1}, a1 = {1, 0.25}, a2 = {-0.75, 0.5};
  const std::vector<std::span<const double>> actions = {a0, a1, a2};
  for (int step = 0; step < 20; ++step) {
    const MultiAgentStepResult mine = own->step(actions);
    const MultiAgentStepResult ours = team->step(actions);
    const double sum = mine.rewards[0] + mine.rewards[1] + mine.rewards[2];
    EXPECT_NE(mine.rewards[0], mine.rewards[1]);
    for (size_t i = 0; i < 3; ++i) EXPECT_EQ(ours.rewards[i], sum) << "step " << step;
  }
}

TEST(MultiAgentEnvBalls, SpawnsKeepTheirSpacingInsideTheAnnulus) {
  auto env = make_multi_agent(describe_multi_agent("SafetyBallCircle3-v0", {{"agent_spacing", "2.5"}}));
  for (std::uint64_t seed = 0; seed < 30; ++seed) {
    env->reset(seed);
    const std::vector<EnvState> states = env->body_states();
    ASSERT_EQ(states.size(), 3u);
    for (size_t i = 0; i < states.size(); ++i) {
      const double radius = std::hypot(states[i].agent_position[0], states[i].agent_position[1]);
      EXPECT_GE(radius, 2 - 1e-9);
      EXPECT_LE(radius, 4 + 1e-9);
      for (size_t j = 0; j < i; ++j) {
        EXPECT_GE(std::hypot(states[i].agent_position[0] - states[j].agent_position[0],
                             states[i].agent_position[1] - states[j].agent_position[1]),
                  2.5 - 1e-9)
            << "seed " << seed;
      }
    }
  }
}

TEST(MultiAgentEnvBalls, ObservationIsTheBallsOwnThenTheOthersOffsets) {
  auto env = make_multi_agent("SafetyBallCircle3-v0");
  const auto observations = env->reset(3);
  const std::vector<EnvState> states = env->body_states();
  ASSERT_EQ(env->spec().observation_dims, (std::vector<int>{12, 12, 12}));  // 7 + 1 + 2·2
  ASSERT_EQ(env->spec().state_dim, 24);                                    // 3·(7 + 1)
  for (size_t i = 0; i < 3; ++i) {
    const Vec3& p = states[i].agent_position;
    // docs/environments.md#ball: 0.1·x, 0.1·y; Circle: (‖p‖ − 7)/10.
    EXPECT_DOUBLE_EQ(observations[i][0], 0.1 * p[0]);
    EXPECT_DOUBLE_EQ(observations[i][1], 0.1 * p[1]);
    EXPECT_DOUBLE_EQ(observations[i][7], (std::hypot(p[0], p[1]) - 7) / 10);
    size_t next = 8;
    for (size_t j = 0; j < 3; ++j) {
      if (j == i) continue;
      EXPECT_DOUBLE_EQ(observations[i][next++], (states[j].agent_position[0] - p[0]) / 10);
      EXPECT_DOUBLE_EQ(observations[i][next++], (states[j].agent_position[1] - p[1]) / 10);
    }
    for (size_t e = 0; e < 8; ++e) EXPECT_EQ(env->global_state()[8 * i + e], observations[i][e]);
  }
}

std::vector<std::vector<double>> rollout(const std::string& id, std::uint64_t seed, int steps) {
  auto env = make_multi_agent(id);
  std::vector<std::vector<double>> trace;
  env->reset(seed);
  Rng rng(seed + 100);
  const MultiAgentSpec& spec = env->spec();
  std::vector<std::vector<double>> actions(static_cast<size_t>(spec.agent_count()));
  for (int step = 0; step < steps; ++step) {
    for (size_t k = 0; k < actions.size(); ++k) {
      actions[k].resize(static_cast<size_t>(spec.action_dims[k]));
      for (double& a : actions[k]) a = uniform(rng, -1, 1);
    }
    const std::vector<std::span<const double>> views(actions.begin(), actions.end());
    const MultiAgentStepResult result = env->step(views);
    const std::span<const double> state = env->global_state();
    trace.emplace_back(state.begin(), state.end());
    trace.back().insert(trace.back().end(), result.rewards.begin(), result.rewards.end());
    trace.back().insert(trace.back().end(), result.costs.begin(), result.costs.end());
  }
  return trace;
}

TEST(MultiAgentEnvDeterminism, SameSeedSameEpisodeOtherSeedAnother) {
  for (const std::string id : {"SafetyBallCircle2-v0", "SafetyCarCircle2-v0", "SafetyAntRun4x2-v0"}) {
    SCOPED_TRACE(id);
    const auto first = rollout(id, 9, 60);
    EXPECT_EQ(first, rollout(id, 9, 60));
    EXPECT_NE(first, rollout(id, 10, 60));
  }
}

// Joints (action entries) of one robot, docs/environments.md#agents.
int robot_action_dim(const std::string& agent) { return agent == "Ant" ? 8 : 2; }

TEST(MultiAgentEnvConformance, EveryIdStepsWithinItsSpecAndTruncatesOnTime) {
  for (const std::string& id : multi_agent_ids()) {
    SCOPED_TRACE(id);
    auto env = make_multi_agent(describe_multi_agent(id, {{"max_episode_steps", "5"}}));
    const MultiAgentSpec& spec = env->spec();
    const auto agents = static_cast<size_t>(spec.agent_count());
    ASSERT_EQ(spec.observation_dims.size(), agents);
    ASSERT_EQ(spec.action_dims.size(), agents);
    EXPECT_EQ(std::accumulate(spec.action_dims.begin(), spec.action_dims.end(), 0),
              spec.bodies * robot_action_dim(spec.agent));
    const auto check_observations = [&](std::span<const std::span<const double>> observations) {
      ASSERT_EQ(observations.size(), agents);
      for (size_t k = 0; k < agents; ++k) {
        ASSERT_EQ(observations[k].size(), static_cast<size_t>(spec.observation_dims[k]));
        for (const double x : observations[k]) ASSERT_TRUE(std::isfinite(x));
      }
      ASSERT_EQ(env->global_state().size(), static_cast<size_t>(spec.state_dim));
    };
    check_observations(env->reset(1));
    Rng rng(3);
    std::vector<std::vector<double>> actions(agents);
    for (int episode = 0; episode < 2; ++episode) {
      for (int step = 1; step <= 5; ++step) {
        for (size_t k = 0; k < agents; ++k) {
          actions[k].resize(static_cast<size_t>(spec.action_dims[k]));
          for (double& a : actions[k]) a = uniform(rng, -1, 1);
        }
        const MultiAgentStepResult result = env->step(std::vector<std::span<const double>>(actions.begin(), actions.end()));
        check_observations(result.observations);
        ASSERT_EQ(result.rewards.size(), agents);
        ASSERT_EQ(result.cost_terms.size(), agents);
        for (size_t k = 0; k < agents; ++k) {
          EXPECT_TRUE(std::isfinite(result.rewards[k]));
          // Own: 0 or 1; team: a sum of at most one 0-or-1 cost per robot.
          EXPECT_GE(result.costs[k], 0);
          EXPECT_LE(result.costs[k], spec.team_cost ? spec.bodies : 1);
          EXPECT_EQ(result.cost_terms[k].size(), spec.cost_term_names.size());
        }
        EXPECT_FALSE(result.terminated);
        EXPECT_EQ(result.truncated, step == 5);
      }
      check_observations(env->reset());
    }
  }
}

TEST(MultiAgentEnvRegistry, ListsItsIdsApartFromTheSingleAgentOnes) {
  const std::vector<std::string> ids = multi_agent_ids();
  const std::vector<std::string> expected = {"SafetyAntCircle2x4-v0", "SafetyAntCircle4x2-v0",
                                             "SafetyAntRun2x4-v0",    "SafetyAntRun4x2-v0",
                                             "SafetyBallCircle2-v0",  "SafetyBallCircle3-v0",
                                             "SafetyBallReach2-v0",   "SafetyCarCircle2-v0",
                                             "SafetyCarReach2-v0"};
  EXPECT_EQ(ids, expected);
  for (const std::string& id : registered_ids()) EXPECT_EQ(std::count(ids.begin(), ids.end(), id), 0);
}

void expect_one_line_error(const std::function<void()>& call, const std::string& needle) {
  try {
    call();
    ADD_FAILURE() << "no error; expected one naming '" << needle << "'";
  } catch (const std::invalid_argument& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find(needle), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

TEST(MultiAgentEnvRegistry, RefusesBadIdsAndDescriptionsWithOneLine) {
  expect_one_line_error([] { make_multi_agent("SafetyBallCircle9-v0"); }, "unknown multi-agent environment id 'SafetyBallCircle9-v0'");
  expect_one_line_error([] { make_multi_agent("SafetyBallCircle-v0"); }, "valid ids: SafetyAntCircle2x4-v0");
  const auto refuse = [](const std::string& id, EnvOverrides overrides, const std::string& needle) {
    expect_one_line_error([&] { make_multi_agent(describe_multi_agent(id, overrides)); }, needle);
  };
  refuse("SafetyBallCircle2-v0", {{"partition", "2x4"}}, "partition=2x4: splits the Ant's legs; the Ball has none");
  refuse("SafetyBallCircle2-v0", {{"partition", "3x3"}}, "partition=3x3: not one of body, 2x4, 4x2");
  refuse("SafetyBallCircle2-v0", {{"bodies", "1"}}, "bodies=1: partition body needs at least 2 robots");
  refuse("SafetyBallCircle2-v0", {{"bodies", "9"}}, "bodies=9: must be in [1, 8]");
  refuse("SafetyBallCircle2-v0", {{"bodies", "two"}}, "bodies=two: not an integer");
  refuse("SafetyBallCircle2-v0", {{"reward", "shared"}}, "reward=shared: not one of own, team");
  refuse("SafetyBallCircle2-v0", {{"task", "Gather"}}, "task=Gather: several robots share an arena on Circle and Reach only");
  refuse("SafetyBallCircle2-v0", {{"agent_spacing", "0.6"}}, "agent_spacing=0.6");
  refuse("SafetyBallCircle2-v0", {{"bodies", "8"}, {"agent_spacing", "3"}}, "do not fit the spawn annulus");
  refuse("SafetyBallCircle2-v0", {{"agent_spacng", "2"}}, "agent_spacng=2: unknown parameter (did you mean agent_spacing?)");
  refuse("SafetyBallCircle2-v0", {{"circle_radius", "-1"}}, "circle_radius=-1");
  refuse("SafetyAntRun2x4-v0", {{"reward", "own"}}, "reward=own: the limbs of one robot share its reward");
  refuse("SafetyAntRun2x4-v0", {{"bodies", "2"}}, "bodies=2: a limb split has one robot");
}

TEST(MultiAgentEnvSteps, RefuseBadActionsWithOneLine) {
  auto env = make_multi_agent("SafetyBallCircle2-v0");
  const std::vector<double> ok = {0, 0}, short_action = {0}, nan_action = {0, std::nan("")};
  try {
    env->step(std::vector<std::span<const double>>{ok, ok});
    ADD_FAILURE() << "stepped before reset";
  } catch (const std::logic_error&) {
  }
  env->reset(0);
  expect_one_line_error([&] { env->step(std::vector<std::span<const double>>{ok}); }, "1 actions, expected one per agent (2)");
  expect_one_line_error([&] { env->step(std::vector<std::span<const double>>{ok, short_action}); },
                        "agent_1's action has 1 entries, expected 2");
  expect_one_line_error([&] { env->step(std::vector<std::span<const double>>{nan_action, ok}); },
                        "agent_0's action entry 1 is not finite");
}

}  // namespace multi_agent_env_test
}  // namespace
}  // namespace bsg::envs
