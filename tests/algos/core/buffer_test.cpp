// The rollout buffer's GAE (docs/algorithms.md#buffer-and-gae) against the original's test oracle
// (docs/algorithms.md#test-oracles) and hand-computed special cases.
#include "algos/core/buffer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace bsg::algos {
namespace {

// The original's test path (docs/algorithms.md#test-oracles): rewards = values = linspace(0, 1, 15), gamma 0.95, lambda 0.97.
Buffer oracle_path(double bootstrap) {
  Buffer buffer(15, 1, 1, BufferOptions{.gamma = 0.95, .lam = 0.97, .lam_c = 0.97});
  const Eigen::VectorXd line = Eigen::VectorXd::LinSpaced(15, 0.0, 1.0);
  for (int t = 0; t < 15; ++t) {
    buffer.store(Eigen::VectorXd::Zero(1), Eigen::VectorXd::Zero(1), line[t], line[t], line[t], line[t], 0.0);
  }
  buffer.finish_path(bootstrap, bootstrap, std::nullopt, PathEnd::epoch_cut);
  return buffer;
}

TEST(Buffer, GaeMatchesOriginalOracleWithBootstrap) {
  const Buffer buffer = oracle_path(1.0);
  const double expected[15] = {3.955461, 4.218778, 4.430889, 4.587431, 4.683670, 4.714470, 4.674257, 4.556980,
                               4.356074, 4.064417, 3.674276, 3.177262, 2.564272, 1.825425, 0.950000};
  for (int t = 0; t < 15; ++t) {
    EXPECT_NEAR(buffer.advantages()[t], expected[t], 1e-6) << "t = " << t;
    EXPECT_NEAR(buffer.cost_advantages()[t], expected[t], 1e-6) << "t = " << t;  // same numbers on the cost path
  }
  EXPECT_NEAR(buffer.value_targets()[0], 3.955461, 1e-6);
  EXPECT_NEAR(buffer.value_targets()[1], 4.290207, 1e-6);
  EXPECT_NEAR(buffer.value_targets()[13], 2.753996, 1e-6);
  EXPECT_NEAR(buffer.value_targets()[14], 1.950000, 1e-6);
  EXPECT_NEAR(buffer.cost_value_targets()[14], 1.950000, 1e-6);
  EXPECT_NEAR(buffer.discounted_returns()[0], 5.103431, 1e-6);
  EXPECT_NEAR(buffer.discounted_returns()[14], 1.950000, 1e-6);
}

TEST(Buffer, GaeMatchesOriginalOracleAtTrueTerminal) {
  const Buffer buffer = oracle_path(0.0);
  EXPECT_NEAR(buffer.advantages()[0], 3.653008, 1e-6);
  EXPECT_NEAR(buffer.advantages()[1], 3.890560, 1e-6);
  EXPECT_NEAR(buffer.advantages()[13], 0.950000, 1e-6);
  EXPECT_NEAR(buffer.advantages()[14], 0.000000, 1e-6);
}

TEST(Buffer, LambdaOneGivesBootstrappedReturnMinusValue) {
  Buffer buffer(4, 1, 1, BufferOptions{.gamma = 0.9, .lam = 1.0, .lam_c = 0.0});
  const double rewards[4] = {1.0, -2.0, 0.5, 3.0};
  const double values[4] = {0.3, 0.1, -0.4, 1.0};
  const double costs[4] = {0.0, 1.0, 1.0, 0.0};
  const double cost_values[4] = {0.5, 0.2, 0.7, 0.1};
  for (int t = 0; t < 4; ++t)
    buffer.store(Eigen::VectorXd::Zero(1), Eigen::VectorXd::Zero(1), rewards[t], costs[t], values[t], cost_values[t], 0.0);
  buffer.finish_path(2.0, 0.25, std::nullopt, PathEnd::episode_end);
  double return_to_go = 2.0;
  for (int t = 3; t >= 0; --t) {
    return_to_go = rewards[t] + 0.9 * return_to_go;
    EXPECT_NEAR(buffer.advantages()[t], return_to_go - values[t], 1e-14);
    EXPECT_NEAR(buffer.discounted_returns()[t], return_to_go, 1e-14);
  }
  // lam_c = 0: the one-step TD error of the cost path.
  for (int t = 0; t < 4; ++t) {
    const double next = t == 3 ? 0.25 : cost_values[t + 1];
    EXPECT_NEAR(buffer.cost_advantages()[t], costs[t] + 0.9 * next - cost_values[t], 1e-14);
  }
}

TEST(Buffer, RewardScalingClipsScaledRewardsButNotReturnsOrCosts) {
  Buffer buffer(3, 1, 1, BufferOptions{.gamma = 1.0, .lam = 0.0, .lam_c = 0.0});
  const double rewards[3] = {2.0, 100.0, -1.0};
  for (int t = 0; t < 3; ++t) buffer.store(Eigen::VectorXd::Zero(1), Eigen::VectorXd::Zero(1), rewards[t], 5.0, 0.0, 0.0, 0.0);
  buffer.finish_path(0.0, 0.0, 4.0, PathEnd::episode_end);
  // lambda = 0, gamma = 1, V = 0: A_t = r~_t = clip(r / (4 + 1e-5), -10, 10).
  EXPECT_NEAR(buffer.advantages()[0], 2.0 / (4.0 + 1e-5), 1e-15);
  EXPECT_EQ(buffer.advantages()[1], 10.0);
  EXPECT_NEAR(buffer.advantages()[2], -1.0 / (4.0 + 1e-5), 1e-15);
  EXPECT_EQ(buffer.cost_advantages()[1], 5.0);          // costs are never scaled
  EXPECT_EQ(buffer.discounted_returns()[0], 101.0);     // G_t uses raw rewards
  EXPECT_EQ(buffer.rewards()[1], 100.0);                // the stored rewards stay raw
  ASSERT_EQ(buffer.episodes().size(), 1u);
  EXPECT_EQ(buffer.episodes()[0].episode_return, 101.0);  // EpRet is raw
  EXPECT_EQ(buffer.episodes()[0].episode_cost, 15.0);
  EXPECT_EQ(buffer.episodes()[0].episode_length, 3);
}

TEST(Buffer, EpisodesCutAtEpochEndAreNotRecordedAndPathsAreIndependent) {
  Buffer buffer(5, 2, 1, BufferOptions{.gamma = 0.5, .lam = 1.0, .lam_c = 1.0});
  const Eigen::Vector2d obs(1.0, 2.0);
  buffer.store(obs, Eigen::VectorXd::Ones(1), 1.0, 0.0, 0.0, 0.0, -1.0);
  buffer.store(obs, Eigen::VectorXd::Ones(1), 1.0, 1.0, 0.0, 0.0, -1.0);
  buffer.finish_path(0.0, 0.0, std::nullopt, PathEnd::episode_end);
  EXPECT_EQ(buffer.current_path_length(), 0);
  for (int t = 0; t < 3; ++t) buffer.store(obs, Eigen::VectorXd::Ones(1), 4.0, 0.0, 0.0, 0.0, -1.0);
  EXPECT_THROW(buffer.check_ready(), std::logic_error);  // last path still open
  buffer.finish_path(8.0, 0.0, std::nullopt, PathEnd::epoch_cut);
  EXPECT_NO_THROW(buffer.check_ready());
  ASSERT_EQ(buffer.episodes().size(), 1u);
  EXPECT_EQ(buffer.episodes()[0].episode_length, 2);
  EXPECT_EQ(buffer.advantages()[1], 1.0);              // first path ends at 0
  EXPECT_EQ(buffer.advantages()[0], 1.5);
  EXPECT_EQ(buffer.advantages()[4], 4.0 + 0.5 * 8.0);  // second path bootstraps 8
  EXPECT_EQ(buffer.observations().row(3), obs.transpose());
  buffer.reset();
  EXPECT_EQ(buffer.size(), 0);
  EXPECT_TRUE(buffer.episodes().empty());
}

TEST(Buffer, BadInputGivesExceptions) {
  EXPECT_THROW(Buffer(0, 1, 1), std::invalid_argument);
  EXPECT_THROW(Buffer(4, 1, 1, BufferOptions{.gamma = 1.5}), std::invalid_argument);
  Buffer buffer(1, 3, 2);
  try {
    buffer.store(Eigen::VectorXd::Zero(2), Eigen::VectorXd::Zero(2), 0, 0, 0, 0, 0);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("observation has 2 entries"), std::string::npos) << e.what();
  }
  EXPECT_THROW(buffer.finish_path(0, 0, std::nullopt, PathEnd::episode_end), std::logic_error);  // empty path
  buffer.store(Eigen::VectorXd::Zero(3), Eigen::VectorXd::Zero(2), 0, 0, 0, 0, 0);
  EXPECT_THROW(buffer.store(Eigen::VectorXd::Zero(3), Eigen::VectorXd::Zero(2), 0, 0, 0, 0, 0), std::length_error);
  EXPECT_THROW(buffer.finish_path(0, 0, -1.0, PathEnd::episode_end), std::invalid_argument);
}

}  // namespace
}  // namespace bsg::algos
