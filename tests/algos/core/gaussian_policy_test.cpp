// The Gaussian policy (docs/algorithms.md#gaussian-policy, #mean-kl) against closed-form densities, KL and entropy.
#include "algos/core/gaussian_policy.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace bsg::algos {
namespace {

TEST(GaussianPolicy, AnnealedStdFollowsTheOriginalSchedule) {
  // docs/algorithms.md#exploration-noise oracle: E = 500.
  EXPECT_NEAR(GaussianPolicy::annealed_std(0, 500), 0.509, 1e-15);
  EXPECT_NEAR(GaussianPolicy::annealed_std(250, 500), 0.2595, 1e-15);
  EXPECT_NEAR(GaussianPolicy::annealed_std(499, 500), 0.010998, 1e-15);
  EXPECT_THROW(GaussianPolicy::annealed_std(500, 500), std::invalid_argument);
  EXPECT_THROW(GaussianPolicy::annealed_std(0, 0), std::invalid_argument);
}

TEST(GaussianPolicy, AnAnnealingThatEndsEarlyHoldsTheMinimumAfterwards) {
  // E = 100, n = 80: 0.499 (1 - k/80) + 0.01 up to epoch 80, then 0.01.
  EXPECT_NEAR(GaussianPolicy::annealed_std(0, 100, 80), 0.509, 1e-15);
  EXPECT_NEAR(GaussianPolicy::annealed_std(40, 100, 80), 0.2595, 1e-15);
  EXPECT_NEAR(GaussianPolicy::annealed_std(79, 100, 80), 0.0162375, 1e-15);
  for (const int k : {80, 90, 99}) EXPECT_NEAR(GaussianPolicy::annealed_std(k, 100, 80), 0.01, 1e-15) << k;
  // n = 0 and n = E are the original schedule, bit for bit.
  for (const int k : {0, 37, 99}) {
    EXPECT_EQ(GaussianPolicy::annealed_std(k, 100, 0), GaussianPolicy::annealed_std(k, 100)) << k;
    EXPECT_EQ(GaussianPolicy::annealed_std(k, 100, 100), GaussianPolicy::annealed_std(k, 100)) << k;
  }
  EXPECT_THROW(GaussianPolicy::annealed_std(0, 100, 101), std::invalid_argument);
  EXPECT_THROW(GaussianPolicy::annealed_std(0, 100, -1), std::invalid_argument);
  EXPECT_THROW(GaussianPolicy::annealed_std(100, 100, 80), std::invalid_argument);
}

TEST(GaussianPolicy, StartsWithStdOneHalfAndMeanNetOfTheRightShape) {
  Rng rng(1);
  GaussianPolicy policy(8, 2, {64, 64}, rng);
  EXPECT_EQ(policy.std(), 0.5);
  EXPECT_EQ(policy.mean_net().layer_sizes(), (std::vector<int>{8, 64, 64, 2}));
  policy.set_annealed_std(0, 500);
  EXPECT_NEAR(policy.std(), 0.509, 1e-15);
  EXPECT_THROW(policy.set_std(0.0), std::invalid_argument);
  EXPECT_THROW(policy.set_std(-0.1), std::invalid_argument);
}

TEST(GaussianPolicy, LogProbMatchesProductOfUnivariateNormalDensities) {
  Rng rng(2);
  GaussianPolicy policy(3, 3, {4}, rng);
  policy.set_std(0.37);
  const Eigen::Vector3d mean(0.1, -0.4, 1.2);
  const Eigen::Vector3d action(0.5, -0.1, 0.9);
  double density = 1.0;
  for (int j = 0; j < 3; ++j) {
    const double z = (action[j] - mean[j]) / 0.37;
    density *= std::exp(-0.5 * z * z) / (0.37 * std::sqrt(2.0 * std::numbers::pi));
  }
  EXPECT_NEAR(policy.log_prob(mean, action), std::log(density), 1e-13);
  Eigen::MatrixXd means(2, 3), actions(2, 3);
  means << mean.transpose(), action.transpose();
  actions << action.transpose(), action.transpose();
  Eigen::VectorXd log_probs(2);
  policy.log_prob_batch(means, actions, log_probs);
  EXPECT_NEAR(log_probs[0], std::log(density), 1e-13);
  EXPECT_NEAR(log_probs[1], 3 * std::log(1.0 / (0.37 * std::sqrt(2.0 * std::numbers::pi))), 1e-13);
}

TEST(GaussianPolicy, SampledActionsHaveTheRightMomentsAndLogProb) {
  Rng init_rng(3), noise_rng(4);
  GaussianPolicy policy(2, 2, {8}, init_rng);
  policy.set_std(0.3);
  const Eigen::Vector2d observation(0.2, -0.7);
  MlpSampleWorkspace workspace;
  Eigen::VectorXd mean(2), action(2);
  policy.mean_action(observation, mean, workspace);
  EXPECT_LT((mean - policy.mean_net().forward(observation)).norm(), 1e-15);
  const int samples = 20000;
  Eigen::Vector2d sum = Eigen::Vector2d::Zero(), squares = Eigen::Vector2d::Zero();
  for (int s = 0; s < samples; ++s) {
    const double log_prob = policy.sample_action(observation, action, noise_rng, workspace);
    EXPECT_NEAR(log_prob, policy.log_prob(mean, action), 1e-12);
    sum += action;
    squares += (action - mean).cwiseAbs2();
  }
  const Eigen::Vector2d sample_mean = sum / samples;
  const Eigen::Vector2d sample_std = (squares / samples).cwiseSqrt();
  for (int j = 0; j < 2; ++j) {
    EXPECT_NEAR(sample_mean[j], mean[j], 4.0 * 0.3 / std::sqrt(samples));
    EXPECT_NEAR(sample_std[j], 0.3, 0.01);
  }
}

TEST(GaussianPolicy, SamplingIsReproducibleFromTheSeed) {
  Rng init_rng(5);
  const GaussianPolicy policy(2, 3, {8}, init_rng);
  MlpSampleWorkspace workspace;
  Eigen::VectorXd a(3), b(3);
  Rng first(42), second(42);
  policy.sample_action(Eigen::Vector2d(1.0, 2.0), a, first, workspace);
  policy.sample_action(Eigen::Vector2d(1.0, 2.0), b, second, workspace);
  EXPECT_EQ(a, b);
}

TEST(GaussianPolicy, EntropyPerDimensionIsHalfLogTwoPiESigmaSquared) {
  Rng rng(6);
  GaussianPolicy policy(2, 2, {4}, rng);
  policy.set_std(0.2);
  EXPECT_NEAR(policy.entropy_per_dimension(), 0.5 * std::log(2.0 * std::numbers::pi * std::numbers::e * 0.04),
              1e-14);
}

TEST(GaussianPolicy, MeanKlIsTrueKlDividedByActionDimension) {
  // KL(N(mu0, s^2 I) || N(mu1, s^2 I)) = |mu0 - mu1|^2 / (2 s^2) per sample;
  // the original's mean runs over samples AND action dims (Q8).
  Rng rng(7);
  GaussianPolicy policy(2, 3, {4}, rng);
  policy.set_std(0.25);
  Eigen::MatrixXd old_means(2, 3), new_means(2, 3);
  old_means << 0.0, 1.0, -1.0, 0.5, 0.5, 0.5;
  new_means << 0.1, 0.8, -1.0, 0.5, 0.2, 0.9;
  const double kl_sample0 = (0.01 + 0.04 + 0.0) / (2 * 0.0625);
  const double kl_sample1 = (0.0 + 0.09 + 0.16) / (2 * 0.0625);
  EXPECT_NEAR(policy.mean_kl(old_means, new_means), (kl_sample0 + kl_sample1) / 2.0 / 3.0, 1e-14);
  EXPECT_EQ(policy.mean_kl(old_means, old_means), 0.0);
}

TEST(GaussianPolicy, WrongSizesGiveExceptions) {
  Rng rng(8);
  const GaussianPolicy policy(4, 2, {8}, rng);
  EXPECT_THROW(policy.log_prob(Eigen::VectorXd::Zero(3), Eigen::VectorXd::Zero(2)), std::invalid_argument);
  Eigen::VectorXd log_probs(3);
  EXPECT_THROW(policy.log_prob_batch(Eigen::MatrixXd::Zero(4, 2), Eigen::MatrixXd::Zero(4, 2), log_probs),
               std::invalid_argument);
  try {
    policy.mean_kl(Eigen::MatrixXd::Zero(4, 2), Eigen::MatrixXd::Zero(3, 2));
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("new_means 3 x 2"), std::string::npos) << e.what();
  }
  MlpSampleWorkspace workspace;
  Eigen::VectorXd action(2);
  Rng noise(1);
  EXPECT_THROW(policy.sample_action(Eigen::VectorXd::Zero(3), action, noise, workspace), std::invalid_argument);
}

}  // namespace
}  // namespace bsg::algos
