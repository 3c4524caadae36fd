// MultiGoal (docs/multi_agent.md#several-robots-on-reach): several robots on
// Reach, each with its own goal, among zones and a Box placed once for all.
// Oracles: the placement rule (reach_spacing from every hazard, agent_spacing
// between robots) checked over many seeds; the goal bonus (+5 while within
// 1.3 m and slow) and the zone cost (planar distance ≤ Ball radius 0.5 m +
// puddle radius 1 m) on hand-made layouts.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "envs/assembly/scene.h"
#include "envs/multi_agent_env.h"

namespace bsg::envs {
namespace {
// Its own names apart from the other files of its test batch (tests/CMakeLists.txt).
namespace multi_goal_env_test {

constexpr double kReachSpacing = 2.5;  // docs/environments.md#reach
constexpr double kBallHeight = 0.5;    // the Ball's centre at rest, radius 0.5 m

double planar(const Vec3& a, const Vec3& b) { return std::hypot(a[0] - b[0], a[1] - b[1]); }

std::vector<Vec3> puddles_of(const MultiAgentEnv& env) {
  std::vector<Vec3> puddles;
  for (const Marking& marking : scene_view(env).markings) {
    if (marking.kind == Marking::Kind::kPuddle) puddles.push_back(marking.position);
  }
  return puddles;
}

TEST(MultiGoalEnv, HazardsArePlacedOnceAndClearOfEveryRobotAndGoal) {
  for (const std::string id : {"SafetyBallReach2-v0", "SafetyCarReach2-v0"}) {
    auto env = make_multi_agent(id);
    ASSERT_EQ(env->spec().bodies, 2);
    for (std::uint64_t seed = 0; seed < 60; ++seed) {
      env->reset(seed);
      const std::vector<Vec3> puddles = puddles_of(*env);
      ASSERT_EQ(puddles.size(), 8u) << id;  // the single-agent Reach's 8, not 8 per robot
      const std::vector<EnvState> states = env->body_states();
      ASSERT_TRUE(states[0].box.has_value());
      EXPECT_FALSE(states[1].box.has_value());  // one Box, robot 0's task holds it
      // The robots spawn at rest: the reset's engine step moves them by far less than 1 mm.
      EXPECT_GE(planar(states[0].agent_position, states[1].agent_position), 1.5 - 1e-3) << id << " seed " << seed;
      for (const EnvState& robot : states) {
        ASSERT_TRUE(robot.goal.has_value());
        EXPECT_GE(planar(robot.agent_position, *robot.goal), kReachSpacing - 1e-3) << id << " seed " << seed;
        for (const Vec3& puddle : puddles) {
          EXPECT_GE(planar(robot.agent_position, puddle), kReachSpacing - 1e-3) << id << " seed " << seed;
          EXPECT_GE(planar(*robot.goal, puddle), kReachSpacing - 1e-9) << id << " seed " << seed;
        }
      }
    }
    // Deterministic from a seed: the same hazards and goals again.
    env->reset(7);
    const std::vector<Vec3> first = puddles_of(*env);
    const Vec3 goal = *env->body_states()[1].goal;
    env->reset(8);
    env->reset(7);
    EXPECT_EQ(puddles_of(*env), first);
    EXPECT_EQ(*env->body_states()[1].goal, goal);
  }
}

// Robot 0 at (−3, −3), robot 1 at (3, −3), at rest; the Box at (0, −6.5);
// six puddles along y = 6.5, two placed by the test.
std::vector<Layout> layouts(const Vec3& goal0, const Vec3& goal1, const Vec3& puddle_a, const Vec3& puddle_b) {
  Layout first, second;
  first.agent_position = {-3, -3, kBallHeight};
  second.agent_position = {3, -3, kBallHeight};
  first.goal = goal0;
  second.goal = goal1;
  first.box = BoxPlacement{{0, -6.5, 0}, {0, 0, 0, 1}, 0};
  for (const double x : {-6.5, -4.0, -1.5, 1.5, 4.0, 6.5}) first.zones.push_back({x, 6.5, 0});
  first.zones.push_back(puddle_a);
  first.zones.push_back(puddle_b);
  return {first, second};
}

MultiAgentStepResult rest_one_step(MultiAgentEnv& env) {
  const std::vector<double> zero = {0, 0};
  const std::vector<std::span<const double>> actions = {zero, zero};
  return env.step(actions);
}

TEST(MultiGoalEnv, EachRobotEarnsTheBonusOfItsOwnGoalOnly) {
  auto env = make_multi_agent("SafetyBallReach2-v0");
  const Vec3 far_a = {-6.5, 0, 0}, far_b = {6.5, 0, 0};
  // Robot 0 stands on its goal, robot 1's goal is 6 m away: +5 for robot 0
  // (d_prev = d = 0), nothing for robot 1 (at rest d_prev − d = 0).
  env->reset_to(layouts({-3, -3, 0}, {3, 3, 0}, far_a, far_b));
  MultiAgentStepResult result = rest_one_step(*env);
  EXPECT_NEAR(result.rewards[0], 5.0, 1e-6);
  EXPECT_NEAR(result.rewards[1], 0.0, 1e-6);
  // Robot 0's goal respawned > 1.5 m (goal_respawn_clearance) from robot 0 and every hazard.
  const std::vector<EnvState> states = env->body_states();
  EXPECT_GT(planar(*states[0].goal, states[0].agent_position), 1.5);
  for (const Vec3& puddle : puddles_of(*env)) EXPECT_GT(planar(*states[0].goal, puddle), 1.5);
  EXPECT_EQ(*states[1].goal, (Vec3{3, 3, 0}));
  // Robot 1 stands on robot 0's goal: another's goal pays nothing.
  env->reset_to(layouts({3, -3, 0}, {-3, 3, 0}, far_a, far_b));
  result = rest_one_step(*env);
  EXPECT_NEAR(result.rewards[0], 0.0, 1e-6);
  EXPECT_NEAR(result.rewards[1], 0.0, 1e-6);
  // Robot 1 on its own goal.
  env->reset_to(layouts({-3, 3, 0}, {3, -3, 0}, far_a, far_b));
  result = rest_one_step(*env);
  EXPECT_NEAR(result.rewards[0], 0.0, 1e-6);
  EXPECT_NEAR(result.rewards[1], 5.0, 1e-6);
}

TEST(MultiGoalEnv, TheSharedPuddlesCostEveryRobotThatTouchesThem) {
  auto env = make_multi_agent("SafetyBallReach2-v0");
  ASSERT_EQ(env->spec().cost_term_names.front(), "number_collisions");
  // Contact at planar distance ≤ 0.5 + 1 = 1.5 m: robot 0 is 1.6 m from a
  // puddle (none), robot 1 1.4 m from the other (one), both placed by robot 0's layout.
  env->reset_to(layouts({-3, 3, 0}, {3, 3, 0}, {-3 + 1.6, -3, 0}, {3 + 1.4, -3, 0}));
  MultiAgentStepResult result = rest_one_step(*env);
  EXPECT_EQ(result.costs[0], 0);
  EXPECT_EQ(result.costs[1], 1);
  EXPECT_EQ(result.cost_terms[0][0].value, 0);
  EXPECT_EQ(result.cost_terms[1][0].value, 1);
  // Both robots within 1.4 m of the same puddle at (0, −3): both pay, once each.
  std::vector<Layout> near = layouts({-3, 3, 0}, {3, 3, 0}, {0, -3, 0}, {6.5, 0, 0});
  near[0].agent_position = {-1.4, -3, kBallHeight};
  near[1].agent_position = {1.4, -3, kBallHeight};
  env->reset_to(near);
  result = rest_one_step(*env);
  EXPECT_EQ(result.costs[0], 1);
  EXPECT_EQ(result.costs[1], 1);
  EXPECT_EQ(result.cost_terms[0][0].value, 1);
  EXPECT_EQ(result.cost_terms[1][0].value, 1);
}

TEST(MultiGoalEnv, ALayoutForAFollowerRobotCarriesNoHazards) {
  auto env = make_multi_agent("SafetyBallReach2-v0");
  std::vector<Layout> bad = layouts({-3, 3, 0}, {3, 3, 0}, {-6.5, 0, 0}, {6.5, 0, 0});
  bad[1].zones = bad[0].zones;
  EXPECT_THROW(env->reset_to(bad), std::invalid_argument);
}

}  // namespace multi_goal_env_test
}  // namespace
}  // namespace bsg::envs
