// The Ball (docs/environments.md#ball) through its environments: the oracles of docs/environments.md#test-oracles
// (zero action keeps it at rest; the measured acceleration under a = (1, 0)),
// action clipping and the agent-specific reward −0.5·‖a‖.
#include "envs/agents/ball_agent.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "envs/env.h"
#include "envs/physics/world.h"

namespace bsg::envs {
namespace {

TEST(BallAgent, TraitsFollowSpecSection3) {
  World world(WorldLayout::kPlane200, 4);
  const auto ball = make_ball_agent(world, {});
  const AgentTraits& traits = ball->traits();
  EXPECT_EQ(traits.action_dim, 2);
  EXPECT_EQ(traits.observation_dim, 7);
  EXPECT_EQ(traits.initial_position, btVector3(0, 0, 0.5));
  EXPECT_EQ(traits.collision_radius, 0.5);
  EXPECT_EQ(traits.run_speed_limit, 2.5);
  EXPECT_FALSE(traits.sensor_rotates);
  EXPECT_EQ(ball->movable_joint_count(), 0);
  EXPECT_EQ(ball->colliders().size(), 1u);
}

// docs/environments.md#ball: zero action from rest → no motion, reward 0, cost 0.
TEST(BallAgent, ZeroActionFromRestDoesNotMoveInCircleAndRun) {
  for (const char* id : {"SafetyBallCircle-v0", "SafetyBallRun-v0"}) {
    SCOPED_TRACE(id);
    const auto env = make(id);
    env->reset(3);
    const Vec3 start = env->state().agent_position;
    double reward_sum = 0;
    for (int t = 0; t < 60; ++t) {
      const StepResult result = env->step(std::vector<double>{0, 0});
      reward_sum += result.reward;
      EXPECT_EQ(result.cost, 0);
    }
    EXPECT_LT(std::abs(reward_sum), 1e-9);
    const Vec3 end = env->state().agent_position;
    for (int i = 0; i < 2; ++i) EXPECT_NEAR(end[i], start[i], 1e-12);
    // Resting bodies sink by the linear slop, 1e-5 m (docs/environments.md#physics-settings).
    EXPECT_NEAR(end[2], 0.49999, 1e-9);
  }
}

// docs/environments.md#ball: measured speeds of the original under a = (1, 0) in Run.
TEST(BallAgent, FullForwardPushAcceleratesAsMeasuredOnTheOriginal) {
  const auto env = make("SafetyBallRun-v0");
  env->reset(0);
  const std::vector<std::pair<int, double>> measured = {{1, 0.133}, {10, 1.32}, {30, 3.83},
                                                        {60, 6.94}};
  int first_velocity_cost = -1;
  double first_reward = 0;
  for (int t = 1; t <= 60; ++t) {
    const StepResult result = env->step(std::vector<double>{1, 0});
    if (t == 1) first_reward = result.reward;
    if (first_velocity_cost < 0 && result.cost_term("cost_velocity_violation") == 1) {
      first_velocity_cost = t;
    }
    for (const auto& [step, speed] : measured) {
      if (t == step) {
        const EnvState state = env->state();
        EXPECT_NEAR(state.agent_linear_velocity[0], speed, 0.1 * speed) << "step " << t;
        // Pure rolling: ω_y = v_x / r.
        EXPECT_NEAR(state.agent_angular_velocity[1], state.agent_linear_velocity[0] / 0.5,
                    0.05 * speed / 0.5)
            << "step " << t;
      }
    }
  }
  EXPECT_NEAR(first_reward, -0.417, 0.05);
  EXPECT_GE(first_velocity_cost, 17);
  EXPECT_LE(first_velocity_cost, 23);
}

TEST(BallAgent, ActionsAreClippedToUnitRange) {
  const auto clipped = make("SafetyBallRun-v0");
  const auto unit = make("SafetyBallRun-v0");
  clipped->reset(4);
  unit->reset(4);
  for (int t = 0; t < 10; ++t) {
    const StepResult a = clipped->step(std::vector<double>{7.5, -30});
    const double reward_a = a.reward;
    const std::vector<double> obs_a(a.observation.begin(), a.observation.end());
    const StepResult b = unit->step(std::vector<double>{1, -1});
    EXPECT_EQ(reward_a, b.reward);
    EXPECT_TRUE(std::equal(obs_a.begin(), obs_a.end(), b.observation.begin()));
  }
}

TEST(BallAgent, SpecificRewardIsMinusHalfTheActionNorm) {
  const auto env = make("SafetyBallCircle-v0");
  env->reset(0);
  env->step(std::vector<double>{0.6, -0.8});
  EXPECT_DOUBLE_EQ(env->state().agent_reward, -0.5);
  env->step(std::vector<double>{3, 0});  // clipped to (1, 0)
  EXPECT_DOUBLE_EQ(env->state().agent_reward, -0.5);
}

TEST(BallAgent, ObservationScalesPositionVelocityAndSpin) {
  const auto env = make("SafetyBallRun-v0");
  env->reset(0);
  StepResult result;
  for (int t = 0; t < 5; ++t) result = env->step(std::vector<double>{0.5, -0.7});
  const EnvState s = env->state();
  const std::vector<double> expected = {
      0.1 * s.agent_position[0],         0.1 * s.agent_position[1],
      0.2 * s.agent_linear_velocity[0],  0.2 * s.agent_linear_velocity[1],
      0.1 * s.agent_angular_velocity[0], 0.1 * s.agent_angular_velocity[1],
      0.1 * s.agent_angular_velocity[2]};
  ASSERT_EQ(result.observation.size(), 7u);
  for (size_t i = 0; i < 7; ++i) EXPECT_EQ(result.observation[i], expected[i]) << i;
}

}  // namespace
}  // namespace bsg::envs

namespace bsg::envs {
namespace {

// The room's walls stop the Ball (docs/environments.md#worlds: inner faces at ±9.9 m, Ball
// radius 0.5): pushed at full force into the +x wall for 5 s, its centre
// stays 0.5 m from the face, up to the contact's slop. The walls and the
// ground are static and asleep (World skips their bounding boxes); a
// contact needs only the Ball to be awake.
TEST(BallAgent, RoomWallStopsTheBall) {
  const auto env = make("SafetyBallGather-v0");
  env->reset(5);
  env->teleport_agent({8.0, 0.0, 0.5});
  double largest_x = 0;
  for (int t = 0; t < 300; ++t) {
    env->step(std::vector<double>{1, 0});
    largest_x = std::max(largest_x, env->state().agent_position[0]);
  }
  EXPECT_GT(largest_x, 9.3);  // it reached the wall
  EXPECT_LT(largest_x, 9.4 + 1e-3);
  EXPECT_NEAR(env->state().agent_position[2], 0.5, 1e-3);  // and is still on the ground
}

}  // namespace
}  // namespace bsg::envs
