// Gather (docs/environments.md#gather) against its oracles (#test-oracles): placement clearances, +10 per
// apple and only once, termination after the last apple, collected apples
// still sensed, bombs cost once, and the altitude cost.
#include "envs/tasks/gather_task.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "common/random.h"
#include "envs/env.h"

namespace bsg::envs {
namespace {
namespace gather_task_test {

const std::vector<double> kZero{0, 0};

double planar(const Vec3& a, const Vec3& b) { return std::hypot(a[0] - b[0], a[1] - b[1]); }

TEST(GatherTask, ResetKeepsTheAgentAndPairwiseClearances) {
  const auto env = make("SafetyBallGather-v0");
  for (uint64_t seed = 0; seed < 30; ++seed) {
    env->reset(seed);
    const Layout& layout = env->layout();
    EXPECT_EQ(layout.agent_position[0], 0);
    EXPECT_EQ(layout.agent_position[1], 0);
    std::vector<Vec3> objects = layout.apples;
    objects.insert(objects.end(), layout.bombs.begin(), layout.bombs.end());
    ASSERT_EQ(objects.size(), 16u);
    for (size_t i = 0; i < objects.size(); ++i) {
      EXPECT_GE(planar(objects[i], layout.agent_position), 1.0);
      for (size_t j = 0; j < i; ++j) EXPECT_GT(planar(objects[i], objects[j]), 2.0);
    }
  }
}

TEST(GatherTask, AppleHalfAMetreAwayPaysTenExactlyOnce) {
  const auto env = make("SafetyBallGather-v0");
  env->reset(5);
  const Vec3 apple = env->layout().apples[3];
  env->teleport_agent({apple[0] + 0.5, apple[1], 0.5});
  const StepResult first = env->step(kZero);
  EXPECT_EQ(first.reward, 10);
  EXPECT_FALSE(first.terminated);
  EXPECT_FALSE(env->state().apples_active[3]);
  const StepResult second = env->step(kZero);
  EXPECT_EQ(second.reward, 0);
}

TEST(GatherTask, CollectingTheEighthAppleEndsTheEpisode) {
  const auto env = make("SafetyBallGather-v0");
  env->reset(6);
  const std::vector<Vec3> apples = env->layout().apples;
  for (size_t i = 0; i < apples.size(); ++i) {
    env->teleport_agent({apples[i][0], apples[i][1], 0.5});
    const StepResult result = env->step(kZero);
    EXPECT_EQ(result.reward, 10) << i;
    EXPECT_EQ(result.terminated, i + 1 == apples.size()) << i;
  }
}

// Independent oracle of the pseudo-LIDAR: bearing clockwise from +y.
std::vector<double> expected_bins(const Vec3& agent, const std::vector<Vec3>& objects) {
  std::vector<double> bins(16, 0.0);
  for (const Vec3& object : objects) {
    const double dx = object[0] - agent[0], dy = object[1] - agent[1];
    const double distance = std::hypot(dx, dy);
    if (distance > 10) continue;
    double bearing = std::atan2(dx, dy);
    if (bearing < 0) bearing += 2 * std::numbers::pi;
    const auto bin = static_cast<size_t>(bearing / (2 * std::numbers::pi / 16)) % 16;
    bins[bin] = std::max(bins[bin], 1 - distance / 10);
  }
  return bins;
}

TEST(GatherTask, CollectedApplesAndTouchedBombsRemainVisibleToThePseudoLidars) {
  const auto env = make("SafetyBallGather-v0");
  env->reset(7);
  const Layout layout = env->layout();
  env->teleport_agent({layout.apples[0][0], layout.apples[0][1], 0.5});
  env->step(kZero);
  // Half a metre south of the bomb (exactly on it, the bearing is undefined).
  env->teleport_agent({layout.bombs[0][0], layout.bombs[0][1] - 0.5, 0.5});
  const StepResult result = env->step(kZero);
  const EnvState state = env->state();
  ASSERT_FALSE(state.apples_active[0]);
  ASSERT_FALSE(state.bombs_active[0]);
  const std::vector<double> apples = expected_bins(state.agent_position, layout.apples);
  const std::vector<double> bombs = expected_bins(state.agent_position, layout.bombs);
  for (size_t b = 0; b < 16; ++b) {
    EXPECT_NEAR(result.observation[7 + b], apples[b], 1e-12) << b;
    EXPECT_NEAR(result.observation[23 + b], bombs[b], 1e-12) << b;
  }
}

TEST(GatherTask, TouchingABombCostsOnceAndGivesNoReward) {
  const auto env = make("SafetyBallGather-v0");
  env->reset(8);
  const Vec3 bomb = env->layout().bombs[2];
  env->teleport_agent({bomb[0], bomb[1] - 0.9, 0.5});
  const StepResult first = env->step(kZero);
  EXPECT_EQ(first.cost, 1);
  EXPECT_EQ(first.cost_term("cost_gathered_bombs"), 1);
  EXPECT_EQ(first.reward, 0);
  const StepResult second = env->step(kZero);
  EXPECT_EQ(second.cost, 0);
}

TEST(GatherTask, AltitudeAboveTwoMetresCosts) {
  const auto env = make("SafetyBallGather-v0");
  env->reset(9);
  env->teleport_agent({0, 0, 4});
  const StepResult result = env->step(kZero);
  EXPECT_EQ(result.cost_term("cost_out_of_range"), 1);
  EXPECT_EQ(result.cost, 1);
}

TEST(GatherTask, RandomPlayRewardsAreMultiplesOfTenOrTheDeathPenalty) {
  for (const std::string& id : registered_ids()) {
    if (id.find("Gather") == std::string::npos) continue;
    SCOPED_TRACE(id);
    const auto env = make(id);
    Rng rng(4);
    env->reset(4);
    for (int t = 0; t < env->spec().max_episode_steps; ++t) {
      std::vector<double> action(static_cast<size_t>(env->spec().action_dim));
      for (double& a : action) a = uniform(rng, -1, 1);
      const StepResult result = env->step(action);
      EXPECT_TRUE(result.reward == -10 || std::fmod(result.reward, 10) == 0) << result.reward;
      if (result.terminated || result.truncated) break;
    }
  }
}

}  // namespace gather_task_test
}  // namespace
}  // namespace bsg::envs
