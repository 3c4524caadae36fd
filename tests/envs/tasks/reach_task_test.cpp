// Reach (docs/environments.md#reach) against its oracles (#test-oracles, #moving-box): placement
// clearances, first-step cost, task observation, puddle and Box costs, the
// goal bonus with an immediate respawn, and both Box clocks.
#include "envs/tasks/reach_task.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "envs/env.h"

namespace bsg::envs {
namespace {
namespace reach_task_test {

const std::vector<double> kZero{0, 0};

double planar(const Vec3& a, const Vec3& b) { return std::hypot(a[0] - b[0], a[1] - b[1]); }

// A layout with everything far from the agent at the origin.
Layout quiet_layout() {
  Layout layout;
  layout.agent_position = {0, 0, 0.5};
  layout.goal = Vec3{5, 5, 0};
  layout.box = BoxPlacement{{-6, 6, 0}, {0, 0, 0, 1}, 0};
  for (int i = 0; i < 8; ++i) layout.zones.push_back({-6.0 + 1.7 * i, -6, 0});
  return layout;
}

TEST(ReachTask, ResetKeepsClearancesAndStartsWithoutCost) {
  const auto env = make("SafetyBallReach-v0");
  for (uint64_t seed = 0; seed < 30; ++seed) {
    const std::span<const double> obs = env->reset(seed);
    const Layout layout = env->layout();
    const Vec3& agent = layout.agent_position;
    const Vec3& goal = *layout.goal;
    EXPECT_GE(planar(goal, agent), 2.5);
    std::vector<Vec3> obstacles = {layout.box->position};
    obstacles.insert(obstacles.end(), layout.zones.begin(), layout.zones.end());
    ASSERT_EQ(obstacles.size(), 9u);
    for (size_t i = 0; i < obstacles.size(); ++i) {
      EXPECT_GE(planar(obstacles[i], agent), 2.5);
      EXPECT_GT(planar(obstacles[i], goal), 2.5);
      for (size_t j = 0; j < i; ++j) EXPECT_GT(planar(obstacles[i], obstacles[j]), 2.5);
    }
    EXPECT_DOUBLE_EQ(*layout.d_prev, planar(goal, agent));
    // Task observation (goal − agent)/20; the reset step does not move the Ball in xy.
    EXPECT_NEAR(obs[55], (goal[0] - agent[0]) / 20, 1e-9);
    EXPECT_NEAR(obs[56], (goal[1] - agent[1]) / 20, 1e-9);
    for (size_t i = 7; i < 55; ++i) {
      EXPECT_GE(obs[i], 0);
      EXPECT_LE(obs[i], 1);
    }
    const StepResult first = env->step(kZero);
    EXPECT_EQ(first.cost, 0);
  }
}

// The obstacles of layout `layout` and whether each keeps the sampler's clearances (2.5 planar
// from `agent`, more than 2.5 from `goal`).
bool obstacles_clear_of(const Layout& layout, const Vec3& agent, const Vec3& goal) {
  std::vector<Vec3> obstacles = {layout.box->position};
  obstacles.insert(obstacles.end(), layout.zones.begin(), layout.zones.end());
  bool clear = true;
  for (const Vec3& obstacle : obstacles) {
    clear = clear && planar(obstacle, agent) >= 2.5 && planar(obstacle, goal) > 2.5;
  }
  return clear;
}

// obstacle_clearance_from stale (the fork, docs/environments.md#the-fork-variant): the clearances
// hold from where agent and goal stood before the reset moved them. First reset: the agent's
// construction position (0, 0) and the goal zone's (0, 0). Later: the first reset's goal (−6, 6)
// and, for the Ball, the previous spawn; for the other agents the first reset's spawn.
void expect_stale_clearances(const std::string& id, bool follows_previous_spawn) {
  const auto env = make(id);
  env->reset(11);
  EXPECT_TRUE(obstacles_clear_of(env->layout(), {0, 0, 0}, {0, 0, 0}));
  const Vec3 first_spawn = env->layout().agent_position;
  Vec3 previous_spawn = first_spawn;
  int clear_of_own_spawn = 0;
  constexpr int kResets = 100;
  for (int k = 0; k < kResets; ++k) {
    env->reset();
    const Layout& layout = env->layout();
    const Vec3 reference = follows_previous_spawn ? previous_spawn : first_spawn;
    EXPECT_TRUE(obstacles_clear_of(layout, reference, {-6, 6, 0})) << id << " reset " << k + 2;
    if (obstacles_clear_of(layout, layout.agent_position, *layout.goal)) ++clear_of_own_spawn;
    previous_spawn = layout.agent_position;
  }
  // Nothing keeps them clear of this episode's own spawn and goal. Oracle by area: each of the
  // 9 obstacles lands within 2.5 m of a uniform spawn in the 14 m square with probability about
  // π·2.5²/14² = 0.1, so about 0.9⁹ ≈ 0.39 of the resets (fewer with the goal) are clear.
  EXPECT_LT(clear_of_own_spawn, kResets / 2) << id;
}

TEST(ReachTask, ForkSamplesObstaclesAgainstTheBallsPreviousSpawn) {
  expect_stale_clearances("SafetyBallReach-fork", true);
}

TEST(ReachTask, ForkSamplesObstaclesAgainstTheOtherAgentsFirstSpawn) {
  expect_stale_clearances("SafetyAntReach-fork", false);
}

TEST(ReachTask, AgentInsideAPuddleCosts) {
  const auto env = make("SafetyBallReach-v0");
  env->reset_to(quiet_layout());
  const Vec3 puddle = env->layout().zones[4];
  // Footprint overlap: ‖agent − puddle‖ − 0.5 − 1.0 ≤ 0.
  env->teleport_agent({puddle[0] + 1.4, puddle[1], 0.5});
  StepResult result = env->step(kZero);
  EXPECT_GE(result.cost_term("number_collisions"), 1);
  EXPECT_EQ(result.cost_term("cost_collisions"), result.cost_term("number_collisions"));
  EXPECT_EQ(result.cost, 1);
  env->teleport_agent({puddle[0], puddle[1] + 1.6, 0.5});
  result = env->step(kZero);
  EXPECT_EQ(result.cost, 0);
}

TEST(ReachTask, TouchingTheBoxCosts) {
  EnvOptions options;  // held phase: the pivot stays put during the episode
  const auto env = make("SafetyBallReach-v0", options);
  Layout layout = quiet_layout();
  layout.box = BoxPlacement{{-5, 5, 0}, {0, 0, 0, 1}, std::numbers::pi / 2};  // pivot c + (0.7, 0)
  env->reset_to(layout);
  for (int t = 0; t < 120; ++t) env->step(kZero);  // the box settles on its pivot at yaw 0
  const BoxState box = env->state().box.value();
  EXPECT_NEAR(box.position[0], -4.3, 0.1);
  env->teleport_agent({box.position[0] + 1.0, box.position[1], 0.5});  // east face at +0.5
  const StepResult result = env->step(kZero);
  EXPECT_EQ(result.cost_term("number_collisions"), 1);
  EXPECT_EQ(result.cost, 1);
}

TEST(ReachTask, EnteringTheGoalPaysFiveAndRespawnsTheGoalInTheSameStep) {
  const auto env = make("SafetyBallReach-v0");
  env->reset_to(quiet_layout());
  const double d_prev = env->state().d_prev.value();
  const Vec3 old_goal = *env->layout().goal;
  env->teleport_agent({old_goal[0] + 0.3, old_goal[1], 0.5});
  const StepResult result = env->step(kZero);
  const EnvState state = env->state();
  const double d = planar(old_goal, state.agent_position);
  EXPECT_NEAR(result.reward, d_prev - d + 5, 1e-12);
  const Vec3 goal = state.goal.value();
  EXPECT_GT(planar(goal, state.agent_position), 1.5);
  EXPECT_GT(planar(goal, state.box->position), 1.5);
  for (const Vec3& zone : env->layout().zones) EXPECT_GT(planar(goal, zone), 1.5);
  EXPECT_DOUBLE_EQ(state.d_prev.value(), planar(goal, state.agent_position));
  EXPECT_NEAR(result.observation[55], (goal[0] - state.agent_position[0]) / 20, 1e-12);
  EXPECT_NEAR(result.observation[56], (goal[1] - state.agent_position[1]) / 20, 1e-12);
  EXPECT_FALSE(result.terminated);
}

TEST(ReachTask, RewardIsProgressTowardsTheGoalPlusOneHundredthOfTheAgentTerm) {
  const auto env = make("SafetyBallReach-v0");
  env->reset(3);
  for (int t = 0; t < 20; ++t) {
    const double d_prev = env->state().d_prev.value();
    const StepResult result = env->step(std::vector<double>{0.4, -0.2});
    const EnvState state = env->state();
    const double d = planar(state.goal.value(), state.agent_position);
    if (result.reward < 4) {
      EXPECT_NEAR(result.reward, d_prev - d + 0.01 * state.agent_reward, 1e-12);
    }
  }
}

TEST(ReachTask, DefaultBoxClockHoldsThePivotAndDrawsANewPhaseEachEpisode) {
  const auto env = make("SafetyBallReach-v0");
  env->reset(1);
  const Vec3 pivot = env->state().box->pivot;
  for (int t = 0; t < 50; ++t) {
    env->step(kZero);
    EXPECT_EQ(env->state().box->pivot, pivot);
  }
  const BoxPlacement first = *env->layout().box;
  EXPECT_NEAR(planar(pivot, first.position), 0.7, 1e-12);
  EXPECT_NEAR(pivot[0], first.position[0] + 0.7 * std::sin(first.phase), 1e-12);
  env->reset();
  EXPECT_NE(env->layout().box->phase, first.phase);
}

TEST(ReachTask, SimulatedBoxClockAdvancesOneRadianPerSimulatedSecond) {
  EnvOptions options;
  options.box_clock = BoxClock::kSimulated;
  const auto env = make("SafetyBallReach-v0", options);
  env->reset(2);
  const BoxPlacement box = *env->layout().box;
  EXPECT_EQ(env->state().box->clock_seconds, 0);
  for (int k = 1; k <= 90; ++k) {
    env->step(kZero);
    const BoxState state = *env->state().box;
    const double t = k / 60.0;
    EXPECT_NEAR(state.clock_seconds, t, 1e-12);
    EXPECT_NEAR(state.pivot[0], box.position[0] + 0.7 * std::sin(t + box.phase), 1e-12);
    EXPECT_NEAR(state.pivot[1], box.position[1] + 0.7 * std::cos(t + box.phase), 1e-12);
  }
  // The phase φ is drawn once; the clock keeps counting across episodes.
  env->reset();
  EXPECT_EQ(env->layout().box->phase, box.phase);
  env->step(kZero);
  EXPECT_NEAR(env->state().box->clock_seconds, 91 / 60.0, 1e-12);
}

TEST(ReachTask, MissingOrMalformedLayoutFieldsAreNamed) {
  const auto env = make("SafetyBallReach-v0");
  Layout layout = quiet_layout();
  layout.goal.reset();
  try {
    env->reset_to(layout);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("goal"), std::string::npos) << e.what();
  }
  layout = quiet_layout();
  layout.zones.pop_back();
  try {
    env->reset_to(layout);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("zones"), std::string::npos) << e.what();
  }
  layout = quiet_layout();
  layout.agent_orientation = {0, 0, 0, 2};
  EXPECT_THROW(env->reset_to(layout), std::invalid_argument);
}

}  // namespace reach_task_test
}  // namespace
}  // namespace bsg::envs
