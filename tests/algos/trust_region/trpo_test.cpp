// TRPO's update (docs/algorithms.md#trpo, #test-oracles): the step's Fisher norm, the accepted
// step's KL and improvement checked with hand-written surrogates, and a
// rejected search leaving theta bit-identical.
#include "algos/trust_region/trpo.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "../algorithm_test_support.h"
#include "algos/trust_region/fisher_vector_product.h"

namespace bsg::algos {
namespace {

using testing::SyntheticBatch;

// The damped Fisher matrix at the policy's current parameters, column by column.
Eigen::MatrixXd dense_fisher(const SyntheticBatch& batch, const RunConfig& config) {
  FisherVectorProduct fisher(batch.policy, batch.observations, testing::single_process(),
                             fisher_vector_product_options(config));
  const Eigen::Index n = fisher.num_parameters();
  Eigen::MatrixXd matrix(n, n);
  Eigen::VectorXd column(n);
  for (Eigen::Index j = 0; j < n; ++j) {
    fisher.apply(Eigen::VectorXd::Unit(n, j), column);
    matrix.col(j) = column;
  }
  return matrix;
}

TEST(Trpo, FullStepHasFisherNormTwoDeltaAndAcceptedStepKeepsKlAndImproves) {
  SyntheticBatch batch(64, 3, 4);
  const RunConfig config = testing::config_for(Algorithm::trpo);
  const Eigen::MatrixXd fisher = dense_fisher(batch, config);
  const Eigen::VectorXd theta_old = batch.policy.mean_net().parameters();
  const Eigen::MatrixXd old_means = batch.means();
  const double reward_before = batch.reward_surrogate();

  PolicySurrogate surrogate = batch.surrogate();
  Trpo trpo(config);
  const PolicyUpdateResult result = trpo.update(testing::inputs_for(batch, surrogate, 0.0, 100.0));

  const int acceptance_step = static_cast<int>(result.value("Misc/AcceptanceStep"));
  ASSERT_GE(acceptance_step, 1);
  const Eigen::VectorXd step = batch.policy.mean_net().parameters() - theta_old;
  // Delta = 0.8^(j-1) alpha x with alpha^2 x^T F x = 2 delta q / (q + 1e-8).
  const double q = result.value("Misc/xHx");
  const double shrink = std::pow(0.8, acceptance_step - 1);
  EXPECT_NEAR(step.dot(fisher * step), shrink * shrink * 2.0 * config.trust_region.target_kl * q / (q + 1e-8), 1e-10);
  EXPECT_NEAR(step.norm(), result.value("Misc/FinalStepNorm"), 1e-12);
  EXPECT_NEAR(step.norm(), shrink * result.value("Misc/Alpha") * result.value("Misc/H_inv_g"), 1e-6 * step.norm());

  const double kl = batch.kl_from(old_means);
  EXPECT_LE(kl, 1.5 * config.trust_region.target_kl);
  EXPECT_NEAR(result.value("KL"), kl, 1e-12);
  EXPECT_GE(batch.reward_surrogate() - reward_before, 0.0);
  EXPECT_NEAR(result.value("Loss/Pi"), -reward_before, 1e-12);
  EXPECT_NEAR(result.value("Loss/DeltaPi"), -(batch.reward_surrogate() - reward_before), 1e-12);
  EXPECT_NEAR(result.value("PolicyRatio"), batch.ratios().mean(), 1e-12);
}

TEST(Trpo, RejectedLineSearchLeavesParametersBitIdentical) {
  SyntheticBatch batch(64, 3, 4);
  RunConfig config = testing::config_for(Algorithm::trpo);
  config.trust_region.kl_accept_factor = 1e-30;  // every trial with a non-zero step exceeds the KL tolerance
  config.trust_region.backtrack_budget = 3;
  const Eigen::VectorXd theta_old = batch.policy.mean_net().parameters();

  PolicySurrogate surrogate = batch.surrogate();
  Trpo trpo(config);
  const PolicyUpdateResult result = trpo.update(testing::inputs_for(batch, surrogate, 0.0, 100.0));

  EXPECT_TRUE(testing::bit_identical(batch.policy.mean_net().parameters(), theta_old));
  EXPECT_EQ(result.value("Misc/AcceptanceStep"), 0.0);
  EXPECT_EQ(result.value("Misc/FinalStepNorm"), 0.0);
  EXPECT_EQ(result.value("KL"), 0.0);
  EXPECT_EQ(result.value("Loss/DeltaPi"), 0.0);
  EXPECT_GT(result.value("Misc/Alpha"), 0.0);  // a step was proposed
}

TEST(Trpo, DiagnosticsFollowTheSpecColumnOrderAndNeverChange) {
  SyntheticBatch batch(64, 3, 4);
  Trpo trpo(testing::config_for(Algorithm::trpo));
  const std::vector<std::string> expected = {"Loss/Pi", "Loss/DeltaPi", "Entropy", "KL", "PolicyRatio",
                                             "Misc/AcceptanceStep", "Misc/Alpha", "Misc/FinalStepNorm",
                                             "Misc/gradient_norm", "Misc/xHx", "Misc/H_inv_g"};
  EXPECT_EQ(trpo.diagnostic_names(), expected);
  for (int epoch = 0; epoch < 2; ++epoch) {
    PolicySurrogate surrogate = batch.surrogate();
    const PolicyUpdateResult result = trpo.update(testing::inputs_for(batch, surrogate, 0.0, 100.0));
    ASSERT_EQ(result.diagnostics.size(), expected.size());
    for (std::size_t i = 0; i < expected.size(); ++i) EXPECT_EQ(result.diagnostics[i].name, expected[i]);
  }
  // Entropy per action dimension: 1/2 + 1/2 log 2 pi + log sigma.
  PolicySurrogate surrogate = batch.surrogate();
  const PolicyUpdateResult result = trpo.update(testing::inputs_for(batch, surrogate, 0.0, 100.0));
  EXPECT_NEAR(result.value("Entropy"), 0.5 + 0.5 * std::log(2.0 * std::numbers::pi) + std::log(0.4), 1e-12);
}

TEST(Trpo, HasNoStateAndIgnoresTheCostStatistics) {
  Trpo trpo(testing::config_for(Algorithm::trpo));
  EXPECT_TRUE(trpo.state().empty());
  EXPECT_NO_THROW(trpo.restore_state({}));
  const std::vector<NamedScalar> foreign = {{"lagrange_multiplier", 1.0}};
  EXPECT_THROW(trpo.restore_state(foreign), std::invalid_argument);
  EXPECT_FALSE(trpo.uses_cost_value_function());
  // J_C is not used by TRPO: NaN (no finished episode) is fine.
  SyntheticBatch batch(64, 3, 4);
  PolicySurrogate surrogate = batch.surrogate();
  EXPECT_NO_THROW(trpo.update(testing::inputs_for(batch, surrogate, std::nan(""), std::nan(""))));
}

}  // namespace
}  // namespace bsg::algos
