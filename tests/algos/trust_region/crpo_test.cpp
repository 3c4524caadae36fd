// CRPO's update (docs/algorithms.md#crpo): which surrogate an epoch climbs, worked out by hand
// from J_C, d and eta; within the tolerance the step is TRPO's bit for bit; beyond it the step
// is TRPO's on a batch whose reward advantages are the negated cost advantages -A^Cj, it
// lowers the hand-written cost surrogate and logs it as Loss/Pi; bad crpo_tolerance values are
// refused naming the key.
#include "algos/trust_region/crpo.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "../algorithm_test_support.h"
#include "algos/training/make_algorithm.h"
#include "algos/trust_region/trpo.h"
#include "common/config_error.h"
#include "common/run_config_resolve.h"

namespace bsg::algos {
namespace {

using testing::SyntheticBatch;

TEST(CrpoRectifiedConstraint, RewardStepUnlessSomeCostExceedsItsLimitPlusTheTolerance) {
  // d = 25, eta = 2: a cost step only once J_C > 27.
  EXPECT_EQ(crpo_rectified_constraint(std::vector<ConstraintEstimate>{{26.9, 25.0}}, 2.0), 0);
  EXPECT_EQ(crpo_rectified_constraint(std::vector<ConstraintEstimate>{{27.0, 25.0}}, 2.0), 0);  // equal: reward
  EXPECT_EQ(crpo_rectified_constraint(std::vector<ConstraintEstimate>{{27.5, 25.0}}, 2.0), 1);
  EXPECT_EQ(crpo_rectified_constraint(std::vector<ConstraintEstimate>{{25.5, 25.0}}, 0.0), 1);
  // Two constraints: excesses J - (d + 1) of 28 - 26 = 2 and 12 - 6 = 6: the second, the larger.
  EXPECT_EQ(crpo_rectified_constraint(std::vector<ConstraintEstimate>{{28.0, 25.0}, {12.0, 5.0}}, 1.0), 2);
  // Equal excesses (30 - 26 = 4, 10 - 6 = 4): the first.
  EXPECT_EQ(crpo_rectified_constraint(std::vector<ConstraintEstimate>{{30.0, 25.0}, {10.0, 5.0}}, 1.0), 1);
  // Only the second is violated (20 <= 26).
  EXPECT_EQ(crpo_rectified_constraint(std::vector<ConstraintEstimate>{{20.0, 25.0}, {7.0, 5.0}}, 1.0), 2);
}

TEST(Crpo, WithinTheToleranceTakesExactlyTheTrpoStep) {
  SyntheticBatch trpo_batch(64, 3, 4);
  SyntheticBatch crpo_batch(64, 3, 4);
  PolicySurrogate trpo_surrogate = trpo_batch.surrogate();
  Trpo trpo(testing::config_for(Algorithm::trpo));
  const PolicyUpdateResult trpo_result = trpo.update(testing::inputs_for(trpo_batch, trpo_surrogate, 0.0, 100.0));
  PolicySurrogate crpo_surrogate = crpo_batch.surrogate();
  Crpo crpo(testing::config_for(Algorithm::crpo));
  // J_C = 26.5 > d = 25 but within d + eta = 27.
  const PolicyUpdateResult crpo_result = crpo.update(testing::inputs_for(crpo_batch, crpo_surrogate, 26.5, 100.0));

  EXPECT_EQ(crpo_result.value("crpo_case"), 0.0);
  ASSERT_GE(trpo_result.value("Misc/AcceptanceStep"), 1.0);
  for (std::size_t i = 0; i < trpo_result.diagnostics.size(); ++i) {
    EXPECT_EQ(crpo_result.diagnostics[i], trpo_result.diagnostics[i]);
  }
  EXPECT_TRUE(testing::bit_identical(crpo_batch.policy.mean_net().parameters(),
                                     trpo_batch.policy.mean_net().parameters()));
}

TEST(Crpo, BeyondTheToleranceTakesTheTrpoStepOnTheNegatedCostAdvantages) {
  SyntheticBatch crpo_batch(64, 3, 4);
  // The oracle: TRPO on the same batch with A_i = -A^C_i, so that its reward step minimises L_C.
  SyntheticBatch oracle_batch(64, 3, 4);
  oracle_batch.advantages = -oracle_batch.cost_advantages;
  const Eigen::MatrixXd old_means = crpo_batch.means();
  const double cost_before = crpo_batch.cost_surrogate();  // L_C(theta_old), by hand

  PolicySurrogate oracle_surrogate = oracle_batch.surrogate();
  Trpo trpo(testing::config_for(Algorithm::trpo));
  const PolicyUpdateResult oracle = trpo.update(testing::inputs_for(oracle_batch, oracle_surrogate, 0.0, 100.0));
  PolicySurrogate crpo_surrogate = crpo_batch.surrogate();
  const RunConfig config = testing::config_for(Algorithm::crpo);
  Crpo crpo(config);
  const PolicyUpdateResult result = crpo.update(testing::inputs_for(crpo_batch, crpo_surrogate, 27.5, 100.0));

  EXPECT_EQ(result.value("crpo_case"), 1.0);
  ASSERT_GE(oracle.value("Misc/AcceptanceStep"), 1.0);
  EXPECT_EQ(result.value("Misc/AcceptanceStep"), oracle.value("Misc/AcceptanceStep"));
  const Eigen::VectorXd theta = crpo_batch.policy.mean_net().parameters();
  const Eigen::VectorXd expected = oracle_batch.policy.mean_net().parameters();
  EXPECT_LE((theta - expected).cwiseAbs().maxCoeff(), 1e-14);
  // The loss is l = L_C: logged at theta_old, lowered by the step within the KL bound.
  EXPECT_NEAR(result.value("Loss/Pi"), cost_before, 1e-12);
  EXPECT_NEAR(result.value("Loss/DeltaPi"), crpo_batch.cost_surrogate() - cost_before, 1e-12);
  EXPECT_LT(crpo_batch.cost_surrogate(), cost_before);
  EXPECT_LE(crpo_batch.kl_from(old_means), 1.5 * config.trust_region.target_kl);
}

TEST(Crpo, WithSeveralConstraintsStepsOnTheMostViolatedOne) {
  SyntheticBatch batch(64, 3, 4);
  // Constraint 2's advantages: another column, so that a step on constraint 1 would differ.
  Eigen::MatrixXd cost_advantages(64, 2);
  cost_advantages.col(0) = batch.cost_advantages;
  cost_advantages.col(1) = batch.advantages.reverse() - batch.cost_advantages;
  PolicySurrogate surrogate(batch.observations, batch.actions, batch.old_log_probs, batch.advantages,
                            cost_advantages);
  RunConfig config = testing::config_for(Algorithm::crpo);
  config.constraints = {{{"cost_outside_bounds"}, 25.0}, {{"cost_velocity_violation"}, 5.0}};
  // Excesses over d + 2: 28 - 27 = 1 and 12 - 7 = 5: constraint 2.
  const std::vector<ConstraintEstimate> constraints = {{28.0, 25.0}, {12.0, 5.0}};
  PolicyUpdateInputs inputs = testing::inputs_for(batch, surrogate, 28.0, 100.0);
  inputs.constraints = constraints;
  Crpo crpo(config);
  const PolicyUpdateResult result = crpo.update(inputs);

  SyntheticBatch oracle_batch(64, 3, 4);
  oracle_batch.advantages = -cost_advantages.col(1);
  PolicySurrogate oracle_surrogate = oracle_batch.surrogate();
  Trpo trpo(testing::config_for(Algorithm::trpo));
  const PolicyUpdateResult oracle = trpo.update(testing::inputs_for(oracle_batch, oracle_surrogate, 0.0, 100.0));

  EXPECT_EQ(result.value("crpo_case"), 2.0);
  ASSERT_GE(oracle.value("Misc/AcceptanceStep"), 1.0);
  EXPECT_LE((batch.policy.mean_net().parameters() - oracle_batch.policy.mean_net().parameters()).cwiseAbs().maxCoeff(),
            1e-14);
}

TEST(Crpo, ColumnsAndNoState) {
  const auto crpo = make_algorithm(testing::config_for(Algorithm::crpo));
  EXPECT_EQ(crpo->name(), "crpo");
  std::vector<std::string> expected = {"Loss/Pi", "Loss/DeltaPi", "Entropy", "KL", "PolicyRatio",
                                       "Misc/AcceptanceStep", "Misc/Alpha", "Misc/FinalStepNorm",
                                       "Misc/gradient_norm", "Misc/xHx", "Misc/H_inv_g", "crpo_case"};
  EXPECT_EQ(crpo->diagnostic_names(), expected);
  EXPECT_TRUE(crpo->state().empty());
  EXPECT_TRUE(crpo->uses_cost_value_function());
}

std::string resolve_error(std::vector<std::string> sets) {
  RunConfigRequest request;
  request.configs_dir = std::filesystem::path(BSG_SOURCE_DIR) / "configs";
  request.set_arguments = std::move(sets);
  try {
    resolve_run_config(request);
  } catch (const ConfigError& error) {
    return error.what();
  }
  return "";
}

TEST(Crpo, BadToleranceKeysAreRefusedNamingTheKey) {
  RunConfigRequest request;
  request.configs_dir = std::filesystem::path(BSG_SOURCE_DIR) / "configs";
  request.set_arguments = {"alg=crpo", "env_id=SafetyBallCircle-v0"};
  const RunConfig shipped = resolve_run_config(request).config;
  EXPECT_EQ(shipped.trust_region.crpo_tolerance, 0.0);  // aims at d (OmniSafe's distance is 2.0)
  // Any excess over d then rectifies: 25.5 against d = 25 is a cost step.
  EXPECT_EQ(crpo_rectified_constraint(std::vector<ConstraintEstimate>{{25.5, 25.0}},
                                      shipped.trust_region.crpo_tolerance), 1);
  EXPECT_TRUE(shipped.use_cost_value_function);

  const std::string negative = resolve_error({"alg=crpo", "env_id=SafetyBallCircle-v0", "crpo_tolerance=-1"});
  EXPECT_NE(negative.find("'crpo_tolerance'"), std::string::npos) << negative;
  EXPECT_NE(negative.find("out of range"), std::string::npos) << negative;
  const std::string text = resolve_error({"alg=crpo", "env_id=SafetyBallCircle-v0", "crpo_tolerance=wide"});
  EXPECT_NE(text.find("'crpo_tolerance'"), std::string::npos) << text;
  const std::string other = resolve_error({"alg=trpo", "env_id=SafetyBallCircle-v0", "crpo_tolerance=1"});
  EXPECT_NE(other.find("'crpo_tolerance' does not apply to alg 'trpo'"), std::string::npos) << other;
  const std::string misspelt = resolve_error({"alg=crpo", "env_id=SafetyBallCircle-v0", "crpo_tolerence=1"});
  EXPECT_NE(misspelt.find("crpo_tolerance"), std::string::npos) << misspelt;  // the suggestion

  RunConfig direct = testing::config_for(Algorithm::crpo);
  direct.trust_region.crpo_tolerance = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(Crpo{direct}, std::invalid_argument);
}

}  // namespace
}  // namespace bsg::algos
