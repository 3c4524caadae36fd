// TRPO-L's update (docs/algorithms.md#trpo-l, #test-oracles): lambda is updated before the policy
// step, lambda = 0 reproduces TRPO exactly, the accepted step keeps the KL
// and improves the Lagrangian surrogate, and lambda survives a checkpoint.
#include "algos/trust_region/lag_trpo.h"

#include <gtest/gtest.h>

#include <cmath>

#include "../algorithm_test_support.h"
#include "algos/lagrange/lagrangian_weights.h"
#include "algos/trust_region/trpo.h"

namespace bsg::algos {
namespace {

using testing::SyntheticBatch;

TEST(LagTrpo, SurrogateWeightsNormaliseByOnePlusLambda) {
  const SurrogateWeights zero = lagrangian_surrogate_weights(0.0);
  EXPECT_EQ(zero.reward, 1.0);
  EXPECT_EQ(zero.cost, 0.0);
  const SurrogateWeights three = lagrangian_surrogate_weights(3.0);
  EXPECT_DOUBLE_EQ(three.reward, 0.25);
  EXPECT_DOUBLE_EQ(three.cost, -0.75);
  EXPECT_THROW(lagrangian_surrogate_weights(-0.1), std::invalid_argument);
}

TEST(LagTrpo, WithLambdaZeroTakesExactlyTheTrpoStep) {
  SyntheticBatch trpo_batch(64, 3, 4);
  SyntheticBatch lag_batch(64, 3, 4);
  RunConfig config = testing::config_for(Algorithm::lag_trpo);
  config.multiplier.lagrangian_multiplier_init = 0.0;  // 1e-5 after the original's max(init, 1e-5)
  config.multiplier.lambda_lr = 0.01;                  // J_C = 0 < d drives lambda to max(0, 1e-5 - 0.25) = 0

  PolicySurrogate trpo_surrogate = trpo_batch.surrogate();
  Trpo trpo(testing::config_for(Algorithm::trpo));
  const PolicyUpdateResult trpo_result = trpo.update(testing::inputs_for(trpo_batch, trpo_surrogate, 0.0, 100.0));
  PolicySurrogate lag_surrogate = lag_batch.surrogate();
  LagTrpo lag_trpo(config);
  const PolicyUpdateResult lag_result = lag_trpo.update(testing::inputs_for(lag_batch, lag_surrogate, 0.0, 100.0));

  EXPECT_EQ(lag_result.value("LagrangeMultiplier"), 0.0);
  ASSERT_GE(trpo_result.value("Misc/AcceptanceStep"), 1.0);
  EXPECT_EQ(lag_result.value("Misc/AcceptanceStep"), trpo_result.value("Misc/AcceptanceStep"));
  EXPECT_TRUE(testing::bit_identical(lag_batch.policy.mean_net().parameters(),
                                     trpo_batch.policy.mean_net().parameters()));
}

TEST(LagTrpo, UpdatesLambdaBeforeThePolicyStepAndImprovesTheLagrangian) {
  SyntheticBatch batch(64, 3, 4);
  RunConfig config = testing::config_for(Algorithm::lag_trpo);
  config.multiplier.lagrangian_multiplier_init = 0.001;
  config.multiplier.lambda_lr = 0.1;
  const double mean_episode_cost = 45.0;                        // J_C - d = 20
  const double lambda = 0.001 + 0.1 * (mean_episode_cost - 25.0);  // 2.001, used by this epoch's step
  const auto lagrangian_loss = [&] {                               // l_L = (-L_R + lambda L_C) / (1 + lambda)
    return (-batch.reward_surrogate() + lambda * batch.cost_surrogate()) / (1.0 + lambda);
  };
  const double loss_before = lagrangian_loss();
  const double cost_before = batch.cost_surrogate();
  const Eigen::MatrixXd old_means = batch.means();

  PolicySurrogate surrogate = batch.surrogate();
  LagTrpo lag_trpo(config);
  const PolicyUpdateResult result = lag_trpo.update(testing::inputs_for(batch, surrogate, mean_episode_cost, 100.0));

  EXPECT_NEAR(result.value("LagrangeMultiplier"), lambda, 1e-15);
  EXPECT_NEAR(lag_trpo.lagrange_multiplier(), lambda, 1e-15);
  EXPECT_NEAR(result.value("Loss/Pi"), loss_before, 1e-12);  // the loss uses the updated lambda
  ASSERT_GE(result.value("Misc/AcceptanceStep"), 1.0);
  EXPECT_LE(batch.kl_from(old_means), 1.5 * config.trust_region.target_kl);
  EXPECT_LE(lagrangian_loss(), loss_before);
  EXPECT_NEAR(result.value("Loss/DeltaPi"), lagrangian_loss() - loss_before, 1e-12);
  // With lambda = 2 the cost surrogate weighs heavily: this batch's step lowers it.
  EXPECT_LT(batch.cost_surrogate(), cost_before);
}

TEST(LagTrpo, LambdaRoundTripsThroughTheCheckpointState) {
  SyntheticBatch batch(64, 3, 4);
  const RunConfig config = testing::config_for(Algorithm::lag_trpo);
  LagTrpo original(config);
  PolicySurrogate surrogate = batch.surrogate();
  original.update(testing::inputs_for(batch, surrogate, 40.0, 100.0));
  const std::vector<NamedScalar> saved = original.state();
  ASSERT_EQ(saved.size(), 1u);
  EXPECT_NEAR(saved[0].value, 0.001 + 0.05 * 15.0, 1e-15);

  LagTrpo restored(config);
  restored.restore_state(saved);
  EXPECT_EQ(restored.lagrange_multiplier(), original.lagrange_multiplier());
  EXPECT_TRUE(restored.uses_cost_value_function());
  EXPECT_THROW(restored.update(testing::inputs_for(batch, surrogate, std::nan(""), 100.0)), std::invalid_argument);
}

TEST(LagTrpo, PidMultiplierSteersThePolicyStepAndLogsItsTerms) {
  testing::expect_pid_multiplier_steers_like_sgd<LagTrpo>(Algorithm::lag_trpo);
}

}  // namespace
}  // namespace bsg::algos
