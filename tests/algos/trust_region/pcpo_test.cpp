// PCPO (docs/algorithms.md#pcpo, #test-oracles): the 2-D projection oracles (KL and L2), the active
// linearised constraint after a projection, v <= 0 giving the TRPO step, the
// small-gradient guard, and end-to-end updates with and without line search.
#include "algos/trust_region/pcpo.h"

#include <gtest/gtest.h>

#include <cmath>

#include "../algorithm_test_support.h"
#include "algos/trust_region/natural_gradient.h"

namespace bsg::algos {
namespace {
namespace pcpo_test {

using testing::SyntheticBatch;
using testing::vec2;

struct PcpoOracle {
  double c;
  PcpoProjection projection;
  double nu;
  double step_x, step_y;
  double half_fisher_norm;  // 1/2 Delta^T F Delta
};

// F = [[2,1],[1,2]], g = (1,1), b = (1,0), delta = 0.5: x = (1/3,1/3), q = 2/3,
// eta = 1.224745, Delta_R = (0.408248, 0.408248).
class PcpoTwoDimensionalOracle : public ::testing::TestWithParam<PcpoOracle> {};

Eigen::MatrixXd oracle_fisher() {
  Eigen::MatrixXd fisher(2, 2);
  fisher << 2.0, 1.0, 1.0, 2.0;
  return fisher;
}

TEST_P(PcpoTwoDimensionalOracle, MatchesTheTable) {
  const PcpoOracle& oracle = GetParam();
  const Eigen::MatrixXd fisher = oracle_fisher();
  PcpoStepOptions options;
  options.target_kl = 0.5;
  options.projection = oracle.projection;
  const PcpoStep step = pcpo_step(testing::dense_operator(fisher), vec2(1.0, 1.0), vec2(1.0, 0.0), oracle.c, options);
  constexpr double kTolerance = 1e-5;
  EXPECT_NEAR(step.q, 2.0 / 3.0, kTolerance);
  EXPECT_NEAR(step.eta, 1.224745, kTolerance);
  EXPECT_NEAR(step.reward_step[0], 0.408248, kTolerance);
  EXPECT_NEAR(step.nu, oracle.nu, kTolerance);
  EXPECT_NEAR(step.full_step[0], oracle.step_x, kTolerance);
  EXPECT_NEAR(step.full_step[1], oracle.step_y, kTolerance);
  EXPECT_NEAR(0.5 * step.full_step.dot(fisher * step.full_step), oracle.half_fisher_norm, 1e-4);
  if (oracle.nu > 0.0) {
    EXPECT_NEAR(oracle.c + step.full_step[0], 0.0, 1e-6);  // c + b^T Delta = 0: the constraint is active
  }
}

constexpr PcpoOracle kOracles[] = {
    {-0.1, PcpoProjection::kl, 0.462372, 0.1, 0.562372, 0.3825},
    {-0.1, PcpoProjection::l2, 0.308248, 0.1, 0.408248, 0.2175},
    {+0.5, PcpoProjection::kl, 1.362372, -0.5, 0.862372, 0.5625},
    {+0.5, PcpoProjection::l2, 0.908248, -0.5, 0.408248, 0.2125},
    {-2.0, PcpoProjection::kl, 0.0, 0.408248, 0.408248, 0.5},
    {-2.0, PcpoProjection::l2, 0.0, 0.408248, 0.408248, 0.5},
};
INSTANTIATE_TEST_SUITE_P(Section14_2, PcpoTwoDimensionalOracle, ::testing::ValuesIn(kOracles));

TEST(PcpoStep, NonPositiveViolationAfterTheRewardStepGivesTheTrpoStep) {
  Rng rng(12);
  const Eigen::MatrixXd fisher = testing::random_spd(6, rng);
  const Eigen::VectorXd g = testing::random_vector(6, rng);
  const Eigen::VectorXd b = testing::random_vector(6, rng);
  const NaturalGradientStep trpo = natural_gradient_step(testing::dense_operator(fisher), g, 0.01);
  const double c = -b.dot(trpo.full_step) - 1e-3;  // v = c + b^T Delta_R = -1e-3
  for (PcpoProjection projection : {PcpoProjection::kl, PcpoProjection::l2}) {
    PcpoStepOptions options;
    options.target_kl = 0.01;
    options.projection = projection;
    const PcpoStep step = pcpo_step(testing::dense_operator(fisher), g, b, c, options);
    EXPECT_NEAR(step.violation_after_reward_step, -1e-3, 1e-12);
    EXPECT_EQ(step.nu, 0.0);
    EXPECT_TRUE(testing::bit_identical(step.full_step, trpo.full_step));
  }
}

TEST(PcpoStep, ProjectionMakesTheLinearisedConstraintActiveInHigherDimensions) {
  Rng rng(13);
  const Eigen::MatrixXd fisher = testing::random_spd(5, rng);
  const Eigen::VectorXd g = testing::random_vector(5, rng);
  const Eigen::VectorXd b = testing::random_vector(5, rng);
  for (PcpoProjection projection : {PcpoProjection::kl, PcpoProjection::l2}) {
    PcpoStepOptions options;
    options.target_kl = 0.01;
    options.projection = projection;
    options.conjugate_gradient.iterations = 25;  // converged CG
    const PcpoStep step = pcpo_step(testing::dense_operator(fisher), g, b, 1.0, options);  // v > 0
    ASSERT_GT(step.nu, 0.0);
    EXPECT_NEAR(1.0 + b.dot(step.full_step), 0.0, 1e-6);
  }
}

TEST(PcpoStep, TinyCostGradientIsNotProjected) {
  PcpoStepOptions options;
  options.target_kl = 0.5;
  const PcpoStep step =
      pcpo_step(testing::dense_operator(oracle_fisher()), vec2(1.0, 1.0), vec2(1e-4, 0.0), 0.5, options);
  EXPECT_EQ(step.nu, 0.0);
  EXPECT_TRUE(testing::bit_identical(step.full_step, step.reward_step));
}

TEST(Pcpo, EndToEndStepPassesTheConstrainedTests) {
  int accepted_updates = 0;
  for (PcpoProjection projection : {PcpoProjection::kl, PcpoProjection::l2}) {
    for (const double mean_episode_cost : {10.0, 40.0}) {
      SyntheticBatch batch(64, 3, 4);
      RunConfig config = testing::config_for(Algorithm::pcpo);
      config.trust_region.pcpo_projection = projection;
      const double c = (mean_episode_cost - 25.0) / (100.0 + 1e-8);
      const testing::BeforeConstrainedUpdate before(batch);

      PolicySurrogate surrogate = batch.surrogate();
      Pcpo pcpo(config);
      const PolicyUpdateResult result = pcpo.update(testing::inputs_for(batch, surrogate, mean_episode_cost, 100.0));
      EXPECT_EQ(result.diagnostics.size(), pcpo.diagnostic_names().size());
      EXPECT_EQ(result.value("Misc/OptimCase"), c >= 0.0 ? 1.0 : 2.0);
      if (result.value("Misc/AcceptanceStep") == 0.0) continue;
      ++accepted_updates;
      testing::expect_passes_constrained_tests(batch, before, c, config.trust_region.target_kl);
    }
  }
  EXPECT_EQ(accepted_updates, 4);
}

TEST(Pcpo, WithoutLineSearchAppliesTheProjectedStep) {
  SyntheticBatch batch(64, 3, 4);
  RunConfig config = testing::config_for(Algorithm::pcpo);
  config.trust_region.pcpo_line_search = false;
  config.trust_region.kl_accept_factor = 1e-30;  // would reject every trial if the search ran
  const Eigen::VectorXd theta_old = batch.policy.mean_net().parameters();
  PolicySurrogate surrogate = batch.surrogate();
  Pcpo pcpo(config);
  const PolicyUpdateResult result = pcpo.update(testing::inputs_for(batch, surrogate, 40.0, 100.0));
  EXPECT_EQ(result.value("Misc/AcceptanceStep"), 1.0);
  const double step_norm = (batch.policy.mean_net().parameters() - theta_old).norm();
  EXPECT_NEAR(step_norm, result.value("Misc/FinalStepNorm"), 1e-12);
  EXPECT_GT(step_norm, 0.0);
}

TEST(Pcpo, RejectedLineSearchLeavesParametersBitIdentical) {
  SyntheticBatch batch(64, 3, 4);
  RunConfig config = testing::config_for(Algorithm::pcpo);
  config.trust_region.kl_accept_factor = 1e-30;
  config.trust_region.backtrack_budget = 2;
  const Eigen::VectorXd theta_old = batch.policy.mean_net().parameters();
  PolicySurrogate surrogate = batch.surrogate();
  Pcpo pcpo(config);
  const PolicyUpdateResult result = pcpo.update(testing::inputs_for(batch, surrogate, 10.0, 100.0));
  EXPECT_EQ(result.value("Misc/AcceptanceStep"), 0.0);
  EXPECT_TRUE(testing::bit_identical(batch.policy.mean_net().parameters(), theta_old));
}

}  // namespace pcpo_test
}  // namespace
}  // namespace bsg::algos
