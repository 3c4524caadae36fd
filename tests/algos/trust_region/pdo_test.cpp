// PDO's update (docs/algorithms.md#pdo, #test-oracles): the Adam multiplier is updated first,
// lambda = 0 reproduces TRPO, the line search tests the reward-only loss
// (Q14) and rejects every step once lambda outweighs the reward, pdo_line_search:
// false applies the full step, and the Adam state survives a checkpoint.
#include "algos/trust_region/pdo.h"

#include <gtest/gtest.h>

#include <cmath>

#include "../algorithm_test_support.h"
#include "algos/trust_region/trpo.h"

namespace bsg::algos {
namespace {

using testing::SyntheticBatch;

TEST(Pdo, SearchDirectionIsGMinusLambdaB) {
  const Eigen::VectorXd p = pdo_search_direction(testing::vec2(1.0, 2.0), testing::vec2(3.0, -1.0), 0.5);
  EXPECT_EQ(p[0], -0.5);
  EXPECT_EQ(p[1], 2.5);
  EXPECT_THROW(pdo_search_direction(Eigen::VectorXd::Ones(2), Eigen::VectorXd::Ones(3), 0.5), std::invalid_argument);
}

TEST(Pdo, WithLambdaZeroTakesExactlyTheTrpoStep) {
  SyntheticBatch trpo_batch(64, 3, 4);
  SyntheticBatch pdo_batch(64, 3, 4);
  RunConfig config = testing::config_for(Algorithm::pdo);
  config.multiplier.lagrangian_multiplier_init = 0.0;  // 1e-5; the Adam step of size ~lr on J_C < d clamps it to 0

  PolicySurrogate trpo_surrogate = trpo_batch.surrogate();
  Trpo trpo(testing::config_for(Algorithm::trpo));
  trpo.update(testing::inputs_for(trpo_batch, trpo_surrogate, 0.0, 100.0));
  PolicySurrogate pdo_surrogate = pdo_batch.surrogate();
  Pdo pdo(config);
  const PolicyUpdateResult result = pdo.update(testing::inputs_for(pdo_batch, pdo_surrogate, 0.0, 100.0));

  EXPECT_EQ(result.value("LagrangeMultiplier"), 0.0);
  ASSERT_GE(result.value("Misc/AcceptanceStep"), 1.0);
  EXPECT_TRUE(testing::bit_identical(pdo_batch.policy.mean_net().parameters(),
                                     trpo_batch.policy.mean_net().parameters()));
}

TEST(Pdo, AdamMultiplierFirstThenRewardOnlyLineSearch) {
  SyntheticBatch batch(64, 3, 4);
  RunConfig config = testing::config_for(Algorithm::pdo);
  config.multiplier.lagrangian_multiplier_init = 0.001;
  config.multiplier.lambda_lr = 0.5;  // lambda_1 = 0.001 + 0.5 (Adam's first step has size lr)
  const double reward_before = batch.reward_surrogate();
  const Eigen::MatrixXd old_means = batch.means();

  PolicySurrogate surrogate = batch.surrogate();
  Pdo pdo(config);
  const PolicyUpdateResult result = pdo.update(testing::inputs_for(batch, surrogate, 30.0, 100.0));

  EXPECT_NEAR(result.value("LagrangeMultiplier"), 0.001 + 0.5 * 5.0 / (5.0 + 1e-8), 1e-12);
  ASSERT_GE(result.value("Misc/AcceptanceStep"), 1.0);
  EXPECT_LE(batch.kl_from(old_means), 1.5 * config.trust_region.target_kl);
  EXPECT_GE(batch.reward_surrogate(), reward_before);  // Q14: the reward surrogate must not decrease
  EXPECT_NEAR(result.value("Loss/Pi"), -reward_before, 1e-12);
  EXPECT_GT(result.value("Misc/cost_gradient_norm"), 0.0);
}

TEST(Pdo, WithoutLineSearchAppliesTheFullStep) {
  SyntheticBatch batch(64, 3, 4);
  RunConfig config = testing::config_for(Algorithm::pdo);
  config.trust_region.pdo_line_search = false;
  config.trust_region.kl_accept_factor = 1e-30;  // would reject every trial if the search ran
  const Eigen::VectorXd theta_old = batch.policy.mean_net().parameters();

  PolicySurrogate surrogate = batch.surrogate();
  Pdo pdo(config);
  const PolicyUpdateResult result = pdo.update(testing::inputs_for(batch, surrogate, 30.0, 100.0));

  EXPECT_EQ(result.value("Misc/AcceptanceStep"), 1.0);
  const double step_norm = (batch.policy.mean_net().parameters() - theta_old).norm();
  EXPECT_GT(step_norm, 0.0);
  EXPECT_NEAR(step_norm, result.value("Misc/Alpha") * result.value("Misc/H_inv_g"), 1e-9);
}

TEST(Pdo, RejectedLineSearchLeavesParametersBitIdentical) {
  SyntheticBatch batch(64, 3, 4);
  RunConfig config = testing::config_for(Algorithm::pdo);
  config.trust_region.kl_accept_factor = 1e-30;
  config.trust_region.backtrack_budget = 2;
  const Eigen::VectorXd theta_old = batch.policy.mean_net().parameters();
  PolicySurrogate surrogate = batch.surrogate();
  Pdo pdo(config);
  const PolicyUpdateResult result = pdo.update(testing::inputs_for(batch, surrogate, 30.0, 100.0));
  EXPECT_EQ(result.value("Misc/AcceptanceStep"), 0.0);
  EXPECT_TRUE(testing::bit_identical(batch.policy.mean_net().parameters(), theta_old));
}

// The cause of the original's PDO missing its limit on BallCircle (docs/algorithms.md#pdo): where
// cost comes with reward (A^C = A here, so b = g), p = g - lambda b = (1 - lambda) g points down
// the reward surrogate once lambda > 1, and every trial of the reward-only line search (a
// shorter step along p) lowers it: the search rejects the step and the policy never moves again.
// Without the search (the shipped default) the step is taken and the cost surrogate falls.
SyntheticBatch batch_where_cost_comes_with_reward() {
  SyntheticBatch batch(64, 3, 4);
  batch.cost_advantages = batch.advantages;
  return batch;
}

RunConfig pdo_with_large_lambda(bool line_search) {
  RunConfig config = testing::config_for(Algorithm::pdo);
  config.multiplier.lambda_optimizer = LambdaOptimizer::sgd;
  config.multiplier.lagrangian_multiplier_init = 3.0;
  config.multiplier.lambda_lr = 0.05;
  config.trust_region.pdo_line_search = line_search;
  return config;
}

TEST(Pdo, RewardOnlyLineSearchRejectsEveryStepOnceLambdaOutweighsTheReward) {
  SyntheticBatch batch = batch_where_cost_comes_with_reward();
  const Eigen::VectorXd theta_old = batch.policy.mean_net().parameters();
  PolicySurrogate surrogate = batch.surrogate();
  Pdo pdo(pdo_with_large_lambda(true));
  const PolicyUpdateResult result = pdo.update(testing::inputs_for(batch, surrogate, 30.0, 100.0));
  EXPECT_GT(result.value("LagrangeMultiplier"), 1.0);
  EXPECT_EQ(result.value("Misc/AcceptanceStep"), 0.0);
  EXPECT_TRUE(testing::bit_identical(batch.policy.mean_net().parameters(), theta_old));
}

TEST(Pdo, WithoutTheLineSearchALargeLambdaLowersTheCostSurrogate) {
  SyntheticBatch batch = batch_where_cost_comes_with_reward();
  const double cost_before = batch.cost_surrogate();
  const Eigen::MatrixXd old_means = batch.means();
  PolicySurrogate surrogate = batch.surrogate();
  Pdo pdo(pdo_with_large_lambda(false));
  const PolicyUpdateResult result = pdo.update(testing::inputs_for(batch, surrogate, 30.0, 100.0));
  EXPECT_GT(result.value("LagrangeMultiplier"), 1.0);
  EXPECT_LT(batch.cost_surrogate(), cost_before);
  EXPECT_GT(batch.kl_from(old_means), 0.0);
  EXPECT_LE(batch.kl_from(old_means), 1.5 * testing::config_for(Algorithm::pdo).trust_region.target_kl);
}

TEST(Pdo, AdamStateRoundTripsThroughTheCheckpoint) {
  const RunConfig config = testing::config_for(Algorithm::pdo);
  SyntheticBatch batch(64, 3, 4);
  Pdo original(config);
  for (double cost : {35.0, 10.0}) {
    PolicySurrogate surrogate = batch.surrogate();
    original.update(testing::inputs_for(batch, surrogate, cost, 100.0));
  }
  const std::vector<NamedScalar> saved = original.state();
  ASSERT_EQ(saved.size(), 4u);
  Pdo restored(config);
  restored.restore_state(saved);
  EXPECT_EQ(restored.state(), saved);

  SyntheticBatch batch_a(64, 5, 6);
  SyntheticBatch batch_b(64, 5, 6);
  PolicySurrogate surrogate_a = batch_a.surrogate();
  PolicySurrogate surrogate_b = batch_b.surrogate();
  const PolicyUpdateResult a = original.update(testing::inputs_for(batch_a, surrogate_a, 28.0, 100.0));
  const PolicyUpdateResult b = restored.update(testing::inputs_for(batch_b, surrogate_b, 28.0, 100.0));
  EXPECT_EQ(a.value("LagrangeMultiplier"), b.value("LagrangeMultiplier"));
  EXPECT_TRUE(testing::bit_identical(batch_a.policy.mean_net().parameters(), batch_b.policy.mean_net().parameters()));
  EXPECT_EQ(restored.diagnostic_names().back(), "LagrangeMultiplier");
}

TEST(Pdo, PidMultiplierSteersThePolicyStepAndLogsItsTerms) {
  testing::expect_pid_multiplier_steers_like_sgd<Pdo>(Algorithm::pdo);
}

}  // namespace
}  // namespace bsg::algos
