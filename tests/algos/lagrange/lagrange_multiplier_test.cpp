// The Lagrange multiplier of TRPO-L and PDO (docs/algorithms.md#trpo-l, #pdo, #test-oracles): the SGD
// and Adam oracles, lambda >= 0, and the checkpoint state.
#include "algos/lagrange/multiplier.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "common/random.h"

namespace bsg::algos {
namespace {

TEST(LagrangeMultiplier, SgdOracleOfSection7_2) {
  LagrangeMultiplier multiplier(0.001, LambdaOptimizer::sgd, 0.01);
  EXPECT_NEAR(multiplier.update(30.0, 25.0), 0.051, 1e-15);  // 0.001 + 0.01 * 5
  EXPECT_EQ(multiplier.update(10.0, 25.0), 0.0);              // max(0, 0.051 - 0.15)
  EXPECT_EQ(multiplier.value(), 0.0);
}

TEST(LagrangeMultiplier, AdamOracleOfSection7_3) {
  LagrangeMultiplier multiplier(0.001, LambdaOptimizer::adam, 0.001);
  // gradient -5: m_hat = -5, v_hat = 25, step +0.001 * 5 / (5 + 1e-8)
  EXPECT_NEAR(multiplier.update(30.0, 25.0), 0.001 + 0.001 * 5.0 / (5.0 + 1e-8), 1e-15);
  EXPECT_NEAR(multiplier.value(), 0.002, 1e-11);
}

TEST(LagrangeMultiplier, AdamMovesByItsRatePerEpochWhateverTheViolation) {
  // PPO-Lag's rule (docs/algorithms.md#ppo-lag): under a constant gradient g = -(J_C - d), Adam's
  // bias-corrected moments are m_hat = g and v_hat = g^2 at every step, so each step is
  // lr |g| / (|g| + 1e-8): after 15 epochs at J_C = 34 against d = 10 (violation 24) lambda is
  // 0.001 + 15 * 0.035 = 0.526, and ten times the violation gives the same lambda. The SGD rule
  // (TRPO-L's) moves by alpha (J_C - d): 0.001 + 15 * 0.05 * 24 = 18.001.
  constexpr int kEpochs = 15;
  for (const double episode_cost : {34.0, 250.0}) {
    LagrangeMultiplier adam(0.001, LambdaOptimizer::adam, 0.035);
    for (int epoch = 0; epoch < kEpochs; ++epoch) adam.update(episode_cost, 10.0);
    const double violation = episode_cost - 10.0;
    EXPECT_NEAR(adam.value(), 0.001 + kEpochs * 0.035 * violation / (violation + 1e-8), 1e-12) << episode_cost;
  }
  LagrangeMultiplier sgd(0.001, LambdaOptimizer::sgd, 0.05);
  for (int epoch = 0; epoch < kEpochs; ++epoch) sgd.update(34.0, 10.0);
  EXPECT_NEAR(sgd.value(), 18.001, 1e-12);
}

TEST(LagrangeMultiplier, InitialValueIsAtLeastTenToTheMinusFive) {
  EXPECT_EQ(LagrangeMultiplier(0.0, LambdaOptimizer::sgd, 0.1).value(), 1e-5);
  EXPECT_EQ(LagrangeMultiplier(0.3, LambdaOptimizer::sgd, 0.1).value(), 0.3);
  EXPECT_THROW(LagrangeMultiplier(-1.0, LambdaOptimizer::sgd, 0.1), std::invalid_argument);
  EXPECT_THROW(LagrangeMultiplier(0.1, LambdaOptimizer::adam, 0.0), std::invalid_argument);
}

TEST(LagrangeMultiplier, NeverNegativeAndSgdIncreasesExactlyWhenCostExceedsLimit) {
  Rng rng(5);
  for (LambdaOptimizer optimizer : {LambdaOptimizer::sgd, LambdaOptimizer::adam}) {
    LagrangeMultiplier multiplier(0.001, optimizer, 0.1);
    for (int epoch = 0; epoch < 300; ++epoch) {
      const double cost = uniform(rng, 0.0, 50.0);
      const double before = multiplier.value();
      const double after = multiplier.update(cost, 25.0);
      ASSERT_GE(after, 0.0);
      if (optimizer == LambdaOptimizer::sgd) {
        if (cost > 25.0) {
          EXPECT_GT(after, before);
        } else {
          EXPECT_LE(after, before);
        }
      }
    }
  }
}

TEST(LagrangeMultiplier, AdamMomentsSurviveTheClampAndTheCheckpoint) {
  LagrangeMultiplier multiplier(0.001, LambdaOptimizer::adam, 0.01);
  for (double cost : {40.0, 0.0, 0.0, 30.0}) multiplier.update(cost, 25.0);
  const std::vector<NamedScalar> saved = multiplier.state();
  ASSERT_EQ(saved.size(), 4u);
  EXPECT_EQ(saved[0].name, "lagrange_multiplier");
  EXPECT_EQ(saved[3].value, 4.0);  // Adam step count

  LagrangeMultiplier restored(0.5, LambdaOptimizer::adam, 0.01);
  restored.restore_state(saved);
  EXPECT_EQ(restored.state(), saved);
  // A multiplier with the same lambda but fresh moments moves differently.
  LagrangeMultiplier fresh(saved[0].value, LambdaOptimizer::adam, 0.01);
  for (double cost : {26.0, 20.0, 27.0}) {
    const double expected = multiplier.update(cost, 25.0);
    EXPECT_EQ(restored.update(cost, 25.0), expected);
    EXPECT_NE(fresh.update(cost, 25.0), expected);
  }
}

TEST(LagrangeMultiplier, RestoreRejectsMismatchedState) {
  LagrangeMultiplier sgd(0.001, LambdaOptimizer::sgd, 0.01);
  LagrangeMultiplier adam(0.001, LambdaOptimizer::adam, 0.01);
  EXPECT_THROW(sgd.restore_state(adam.state()), std::invalid_argument);
  EXPECT_THROW(adam.restore_state(sgd.state()), std::invalid_argument);
  const std::vector<NamedScalar> negative = {{"lagrange_multiplier", -0.5}};
  EXPECT_THROW(sgd.restore_state(negative), std::invalid_argument);
  const std::vector<NamedScalar> renamed = {{"lambda", 0.5}};
  EXPECT_THROW(sgd.restore_state(renamed), std::invalid_argument);
  EXPECT_THROW(sgd.update(std::nan(""), 25.0), std::invalid_argument);
}

}  // namespace
}  // namespace bsg::algos
