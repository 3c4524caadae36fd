// Run (docs/environments.md#run) against its oracles (#test-oracles): reset near the origin, progress
// equal to 60·Δx for motion along x, the lane and speed costs.
#include "envs/tasks/run_task.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "envs/env.h"

namespace bsg::envs {
namespace {

TEST(RunTask, PotentialIsMinusSixtyTimesTheDistanceToTheTarget) {
  EXPECT_DOUBLE_EQ(run_potential(0, 0), -60000.0);
  EXPECT_DOUBLE_EQ(run_potential(1000, 3), -180.0);
  EXPECT_DOUBLE_EQ(run_potential(997, -4), -300.0);
}

TEST(RunTask, ResetStaysWithinOneCentimetreOfTheOrigin) {
  const auto env = make("SafetyBallRun-v0");
  for (uint64_t seed = 0; seed < 30; ++seed) {
    env->reset(seed);
    const Layout& layout = env->layout();
    EXPECT_LE(std::abs(layout.agent_position[0]), 0.01);
    EXPECT_LE(std::abs(layout.agent_position[1]), 0.01);
    EXPECT_EQ(layout.phi_prev.value(),
              run_potential(layout.agent_position[0], layout.agent_position[1]));
  }
}

// docs/environments.md#run (with the lateral term's negative sign): Φ(p) − Φ_prev = 60·Δx up to
// the lateral term −60·Δ(y²)/2000.
TEST(RunTask, ProgressIsSixtyTimesTheForwardDisplacement) {
  const auto env = make("SafetyBallRun-v0");
  env->reset(9);
  for (const double dx : {0.5, 2.0, -1.0, 10.0}) {
    const Vec3 p = env->state().agent_position;
    const double y = p[1];
    env->teleport_agent({p[0] + dx, y, p[2]});
    const StepResult result = env->step(std::vector<double>{0, 0});
    const Vec3 q = env->state().agent_position;
    const double moved = q[0] - p[0];
    EXPECT_NEAR(moved, dx, 1e-9);
    EXPECT_NEAR(result.reward, 60 * moved - 60 * (q[1] * q[1] - y * y) / 2000, 1e-6);
    EXPECT_NEAR(result.reward, 60 * dx, 1e-6);
  }
}

TEST(RunTask, CostIsOneOutsideTheLane) {
  const auto env = make("SafetyBallRun-v0");
  env->reset(1);
  for (const auto& [y, expected] :
       std::vector<std::pair<double, double>>{{2.5, 1}, {1.9, 0}, {-2.1, 1}, {-1.5, 0}}) {
    env->teleport_agent({5, y, 0.5});
    const StepResult result = env->step(std::vector<double>{0, 0});
    EXPECT_EQ(result.cost, expected) << "y = " << y;
    EXPECT_EQ(result.cost_term("cost_outside_bounds"), expected);
    EXPECT_EQ(result.cost_term("cost_velocity_violation"), 0);
  }
}

TEST(RunTask, CostIsOneAboveTheSpeedLimitAndCappedAtOne) {
  const auto env = make("SafetyBallRun-v0");
  env->reset(1);
  StepResult result;
  double previous_speed = 0;
  for (int t = 0; t < 60; ++t) {
    result = env->step(std::vector<double>{0.6, 0.8});
    const EnvState s = env->state();
    const double speed = std::hypot(s.agent_linear_velocity[0], s.agent_linear_velocity[1]);
    EXPECT_EQ(result.cost_term("cost_velocity_violation"), speed > 2.5 ? 1 : 0) << t;
    previous_speed = speed;
  }
  EXPECT_GT(previous_speed, 2.5);
  // Outside the lane and too fast: both terms, cost capped at 1.
  EXPECT_EQ(result.cost_term("cost_outside_bounds"), 1);
  EXPECT_EQ(result.cost, 1);
}

TEST(RunTask, InjectedPhiPrevIsUsedForTheFirstReward) {
  const auto env = make("SafetyBallRun-v0");
  Layout layout;
  layout.agent_position = {0, 0, 0.5};
  layout.phi_prev = run_potential(0, 0) - 1.0;  // pretend the agent came from 1/60 m behind
  env->reset_to(layout);
  const StepResult result = env->step(std::vector<double>{0, 0});
  EXPECT_NEAR(result.reward, 1.0, 1e-9);
}

}  // namespace
}  // namespace bsg::envs
