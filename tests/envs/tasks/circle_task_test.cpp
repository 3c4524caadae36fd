// Circle (docs/environments.md#circle) against its oracles (#test-oracles): reset annulus, task
// observation range, the |x| > 6 cost by teleport, and the reward core.
#include "envs/tasks/circle_task.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "envs/env.h"

namespace bsg::envs {
namespace {

// docs/environments.md#circle example: p = (3, 0), v = (0, −1) → 0.1·3/5.
TEST(CircleTask, RewardCoreRewardsClockwiseMotion) {
  EXPECT_DOUBLE_EQ(circle_reward_core(3, 0, 0, -1), 0.06);
  EXPECT_DOUBLE_EQ(circle_reward_core(3, 0, 0, 1), -0.06);
  EXPECT_DOUBLE_EQ(circle_reward_core(3, 0, 2, 0), 0.0);  // radial
  // Largest on the radius-7 circle: denominator 1 + |‖p‖ − 7|.
  EXPECT_DOUBLE_EQ(circle_reward_core(0, 7, 1, 0), 0.7);
  EXPECT_DOUBLE_EQ(circle_reward_core(0, 9, 1, 0), 0.9 / 3);
}

// docs/environments.md#circle.
TEST(CircleTask, ResetPlacesTheAgentInTheAnnulusFacingClockwise) {
  const auto env = make("SafetyBallCircle-v0");
  for (uint64_t seed = 0; seed < 50; ++seed) {
    const std::span<const double> obs = env->reset(seed);
    const Layout& layout = env->layout();
    const double x = layout.agent_position[0], y = layout.agent_position[1];
    const double radius = std::hypot(x, y);
    EXPECT_GE(radius, 2);
    EXPECT_LE(radius, 4);
    EXPECT_GE(obs.back(), -0.5);
    EXPECT_LE(obs.back(), -0.3);
    EXPECT_NEAR(obs.back(), (radius - 7) / 10, 1e-6);
    // Yaw = atan2(−y, −x) + π/2: body +x along the clockwise tangent (y, −x)/‖p‖.
    const Quat& q = layout.agent_orientation;
    const double yaw = 2 * std::atan2(q[2], q[3]);
    EXPECT_NEAR(std::cos(yaw), y / radius, 1e-12);
    EXPECT_NEAR(std::sin(yaw), -x / radius, 1e-12);
    const StepResult first = env->step(std::vector<double>{1, 1});
    EXPECT_EQ(first.cost, 0);
  }
}

TEST(CircleTask, CostIsOneExactlyOutsideTheBandAbsXAbove6) {
  const auto env = make("SafetyBallCircle-v0");
  env->reset(1);
  const std::vector<double> zero{0, 0};
  for (const auto& [x, expected] : std::vector<std::pair<double, double>>{
           {6.5, 1}, {5.9, 0}, {-6.5, 1}, {-5.9, 0}, {0, 0}}) {
    env->teleport_agent({x, 8.5, 0.5});
    const StepResult result = env->step(zero);
    EXPECT_EQ(result.cost, expected) << "x = " << x;
    EXPECT_EQ(result.cost_term("cost_outside_bounds"), expected) << "x = " << x;
  }
}

TEST(CircleTask, RewardOfTheEnvironmentIsCorePlusOneHundredthOfTheAgentTerm) {
  const auto env = make("SafetyBallCircle-v0");
  env->reset(2);
  for (int t = 0; t < 30; ++t) {
    const StepResult result = env->step(std::vector<double>{0.3, -0.9});
    const EnvState s = env->state();
    const double expected =
        circle_reward_core(s.agent_position[0], s.agent_position[1], s.agent_linear_velocity[0],
                           s.agent_linear_velocity[1]) +
        0.01 * s.agent_reward;
    EXPECT_DOUBLE_EQ(result.reward, expected);
  }
}

TEST(CircleTask, LayoutForAnotherTaskIsRejected) {
  const auto env = make("SafetyBallCircle-v0");
  Layout layout;
  layout.agent_position = {3, 0, 0.5};
  layout.goal = Vec3{1, 1, 0};
  EXPECT_THROW(env->reset_to(layout), std::invalid_argument);
}

}  // namespace
}  // namespace bsg::envs
