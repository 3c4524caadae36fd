// CPO (docs/algorithms.md#cpo, #test-oracles): the 2-D oracles of all four cases under both r
// sign conventions (Q10), case 4, case 3 = the TRPO step, the degenerate-A
// guard, one end-to-end update with the constrained line search, and the
// recovery (case 1) that the original sign leaves at a zero step.
#include "algos/trust_region/cpo.h"

#include <gtest/gtest.h>

#include <cmath>

#include "../algorithm_test_support.h"
#include "algos/trust_region/natural_gradient.h"

namespace bsg::algos {
namespace {

using testing::SyntheticBatch;
using testing::vec2;

struct CpoOracle {
  double c;
  CpoRSign r_sign;
  CpoCase expected_case;
  double B;
  double lambda_star;
  double nu_star;
  double step_x, step_y;
};

// F = I, g = (1,1), b = (1,0), delta = 0.5: q = 2, r = 1, s = 1, A = 1 (docs/algorithms.md#test-oracles).
class CpoTwoDimensionalOracle : public ::testing::TestWithParam<CpoOracle> {};

TEST_P(CpoTwoDimensionalOracle, MatchesTheTable) {
  const CpoOracle& oracle = GetParam();
  CpoStepOptions options;
  options.target_kl = 0.5;
  options.r_sign = oracle.r_sign;
  const CpoStep step = cpo_step(testing::dense_operator(Eigen::MatrixXd::Identity(2, 2)), vec2(1.0, 1.0),
                                vec2(1.0, 0.0), oracle.c, options);
  constexpr double kTolerance = 1e-5;  // the table's digits; CG's 1e-6 epsilons shift the 7th
  EXPECT_EQ(step.optim_case, oracle.expected_case);
  EXPECT_NEAR(step.q, 2.0, kTolerance);
  EXPECT_NEAR(step.r, 1.0, kTolerance);  // logged r = g^T p under both conventions
  EXPECT_NEAR(step.s, 1.0, kTolerance);
  EXPECT_NEAR(step.A, 1.0, kTolerance);
  EXPECT_NEAR(step.B, oracle.B, kTolerance);
  EXPECT_NEAR(step.lambda_star, oracle.lambda_star, kTolerance);
  EXPECT_NEAR(step.nu_star, oracle.nu_star, kTolerance);
  EXPECT_NEAR(step.full_step[0], oracle.step_x, kTolerance);
  EXPECT_NEAR(step.full_step[1], oracle.step_y, kTolerance);
}

constexpr CpoOracle kOracles[] = {
    {-0.1, CpoRSign::original, CpoCase::constraint_cuts_region, 0.99, 1.414214, 0.0, 0.707107, 0.707107},
    {+0.1, CpoRSign::original, CpoCase::feasible_recovery, 0.99, 1.414214, 0.0, 0.707107, 0.707107},
    {+2.0, CpoRSign::original, CpoCase::infeasible_recovery, -3.0, 0.0, 1.0, -1.0, 0.0},
    {-2.0, CpoRSign::original, CpoCase::region_feasible, -3.0, 1.414214, 0.0, 0.707107, 0.707107},
    {-0.1, CpoRSign::corrected, CpoCase::constraint_cuts_region, 0.99, 1.005038, 0.899496, 0.100000, 0.994987},
    {+0.1, CpoRSign::corrected, CpoCase::feasible_recovery, 0.99, 1.005038, 1.100504, -0.100000, 0.994987},
    {+2.0, CpoRSign::corrected, CpoCase::infeasible_recovery, -3.0, 0.0, 1.0, -1.0, 0.0},
    {-2.0, CpoRSign::corrected, CpoCase::region_feasible, -3.0, 1.414214, 0.0, 0.707107, 0.707107},
};
INSTANTIATE_TEST_SUITE_P(Section14_2, CpoTwoDimensionalOracle, ::testing::ValuesIn(kOracles));

TEST(CpoStep, CorrectedSignSolvesTheLinearQuadraticSubproblem) {
  // max g^T D s.t. 1/2 D^T D <= delta, c + b^T D <= 0 with F = I, g = (1,1), b = (1,0),
  // delta = 0.5, c = -0.1: the optimum sits on both constraints, D_1 = 0.1, D_2 = sqrt(1 - 0.01).
  CpoStepOptions options;
  options.target_kl = 0.5;
  options.r_sign = CpoRSign::corrected;
  const CpoStep step = cpo_step(testing::dense_operator(Eigen::MatrixXd::Identity(2, 2)), vec2(1.0, 1.0),
                                vec2(1.0, 0.0), -0.1, options);
  EXPECT_NEAR(step.full_step[0], 0.1, 1e-5);
  EXPECT_NEAR(step.full_step[1], std::sqrt(0.99), 1e-5);
  EXPECT_NEAR(-0.1 + step.full_step[0], 0.0, 1e-5);             // cost constraint active
  EXPECT_NEAR(0.5 * step.full_step.squaredNorm(), 0.5, 1e-5);  // trust region active
}

TEST(CpoStep, CaseThreeIsTheTrpoStep) {
  Rng rng(11);
  const Eigen::MatrixXd fisher = testing::random_spd(6, rng);
  const Eigen::VectorXd g = testing::random_vector(6, rng);
  const Eigen::VectorXd b = testing::random_vector(6, rng);
  CpoStepOptions options;
  options.target_kl = 0.01;
  // c^2 > 2 delta s makes B < 0 with c < 0: the whole trust region is feasible.
  const double s = b.dot(fisher.ldlt().solve(b));
  const double c = -2.0 * std::sqrt(2.0 * options.target_kl * s);
  const CpoStep step = cpo_step(testing::dense_operator(fisher), g, b, c, options);
  ASSERT_EQ(step.optim_case, CpoCase::region_feasible);
  const NaturalGradientStep trpo = natural_gradient_step(testing::dense_operator(fisher), g, options.target_kl);
  EXPECT_TRUE(testing::bit_identical(step.full_step, trpo.full_step));
  EXPECT_NEAR(step.lambda_star, 1.0 / trpo.step_size, 1e-15);
  EXPECT_EQ(step.nu_star, 0.0);
}

TEST(CpoStep, TinyCostGradientWhileFeasibleIsCaseFour) {
  CpoStepOptions options;
  options.target_kl = 0.5;
  const CpoStep step = cpo_step(testing::dense_operator(Eigen::MatrixXd::Identity(2, 2)), vec2(1.0, 1.0),
                                vec2(1e-4, 0.0), -1e-6, options);
  EXPECT_EQ(step.optim_case, CpoCase::negligible_cost_gradient);
  EXPECT_EQ(step.A, 0.0);
  EXPECT_EQ(step.B, 0.0);
  EXPECT_NEAR(step.full_step[0], std::sqrt(0.5), 1e-6);
  EXPECT_NEAR(step.full_step[1], std::sqrt(0.5), 1e-6);
  // The same gradient while infeasible is not case 4.
  EXPECT_NE(cpo_step(testing::dense_operator(Eigen::MatrixXd::Identity(2, 2)), vec2(1.0, 1.0), vec2(1e-4, 0.0),
                     1e-6, options).optim_case,
            CpoCase::negligible_cost_gradient);
}

TEST(CpoStep, NegativeAIsAnErrorUnlessClamped) {
  // g = b: A = q - r^2/s is 0 in exact arithmetic, and CG's 1e-6 epsilons make it about -1e-6.
  CpoStepOptions options;
  options.target_kl = 0.5;
  const LinearOperator identity = testing::dense_operator(Eigen::MatrixXd::Identity(2, 2));
  EXPECT_THROW(cpo_step(identity, vec2(1.0, 0.0), vec2(1.0, 0.0), 0.1, options), std::runtime_error);
  options.clamp_a = true;
  const CpoStep step = cpo_step(identity, vec2(1.0, 0.0), vec2(1.0, 0.0), 0.1, options);
  EXPECT_EQ(step.optim_case, CpoCase::feasible_recovery);
  EXPECT_EQ(step.A, 0.0);
  EXPECT_TRUE(step.full_step.allFinite());
}

TEST(Cpo, EndToEndStepPassesTheConstrainedTests) {
  int accepted_updates = 0;
  for (const double mean_episode_cost : {10.0, 40.0}) {
    SyntheticBatch batch(64, 3, 4);
    RunConfig config = testing::config_for(Algorithm::cpo);
    config.trust_region.target_kl = 0.01;
    const double c = (mean_episode_cost - 25.0) / (100.0 + 1e-8);
    const testing::BeforeConstrainedUpdate before(batch);

    PolicySurrogate surrogate = batch.surrogate();
    Cpo cpo(config);
    const PolicyUpdateResult result = cpo.update(testing::inputs_for(batch, surrogate, mean_episode_cost, 100.0));
    ASSERT_EQ(result.diagnostics.size(), cpo.diagnostic_names().size());
    for (std::size_t i = 0; i < result.diagnostics.size(); ++i) {
      EXPECT_EQ(result.diagnostics[i].name, cpo.diagnostic_names()[i]);
    }
    EXPECT_EQ(result.value("Misc/OptimCase") >= 2.0, c < 0.0);
    if (result.value("Misc/AcceptanceStep") == 0.0) continue;
    ++accepted_updates;
    testing::expect_passes_constrained_tests(batch, before, c, config.trust_region.target_kl);
  }
  EXPECT_EQ(accepted_updates, 2);
}

TEST(CpoStep, OriginalSignRecoveryStepRaisesTheLinearisedCost) {
  // Case 1 of the 2-D oracle (c = +0.1): the original's lambda* = sqrt(2) and nu* = (sqrt(2) 0.1 - 1)_+ = 0
  // give D = x / lambda* = (1, 1)/sqrt(2), so b^T D = 0.707 > 0: every fraction 0.8^j D raises the
  // linearised cost, and the line search's test D_j <= max(-c, 0) = 0 rejects them all. The corrected
  // D = (-0.1, 0.99499) ends on the boundary c + b^T D = 0 at the trust region's edge 1/2 D^T D = delta.
  const LinearOperator identity = testing::dense_operator(Eigen::MatrixXd::Identity(2, 2));
  CpoStepOptions options;
  options.target_kl = 0.5;
  const CpoStep original = cpo_step(identity, vec2(1.0, 1.0), vec2(1.0, 0.0), 0.1, options);
  EXPECT_EQ(original.nu_star, 0.0);
  EXPECT_NEAR(original.full_step[0], 1.0 / std::sqrt(2.0), 1e-5);  // b^T D
  options.r_sign = CpoRSign::corrected;
  const CpoStep corrected = cpo_step(identity, vec2(1.0, 1.0), vec2(1.0, 0.0), 0.1, options);
  EXPECT_NEAR(0.1 + corrected.full_step[0], 0.0, 1e-5);
  EXPECT_NEAR(0.5 * corrected.full_step.squaredNorm(), 0.5, 1e-5);
}

TEST(Cpo, OriginalSignLeavesARecoveryWithAlignedCostAtZeroStep) {
  // Cost advantages that share most of the reward advantages' direction (r = g^T F^-1 b > 0, as on
  // BallCircle, where a faster ball earns and costs more) and an episode cost just over the limit
  // (case 1): the original sign keeps nu* = 0, its step climbs the cost surrogate and no fraction
  // passes the cost test, so the policy stays put; the corrected sign steps and lowers L_C.
  for (const CpoRSign sign : {CpoRSign::original, CpoRSign::corrected}) {
    SyntheticBatch batch(64, 3, 4);
    Rng rng(5);
    for (Eigen::Index i = 0; i < batch.advantages.size(); ++i) {
      batch.cost_advantages[i] = 0.8 * batch.advantages[i] + 0.6 * standard_normal(rng);
    }
    RunConfig config = testing::config_for(Algorithm::cpo);
    config.trust_region.target_kl = 0.01;
    config.trust_region.cpo_r_sign = sign;
    constexpr double kEpisodeCost = 25.5;  // c = (25.5 - 25)/100 = 0.005, B = 2 delta - c^2/s > 0
    const double c = (kEpisodeCost - 25.0) / (100.0 + 1e-8);
    const Eigen::VectorXd theta_old = batch.policy.mean_net().parameters();
    const testing::BeforeConstrainedUpdate before(batch);
    PolicySurrogate surrogate = batch.surrogate();
    Cpo cpo(config);
    const PolicyUpdateResult result = cpo.update(testing::inputs_for(batch, surrogate, kEpisodeCost, 100.0));
    ASSERT_EQ(result.value("Misc/OptimCase"), static_cast<double>(CpoCase::feasible_recovery));
    ASSERT_GT(result.value("Misc/r"), 0.0);
    if (sign == CpoRSign::original) {
      EXPECT_EQ(result.value("Misc/Nu_star"), 0.0);
      EXPECT_EQ(result.value("Misc/AcceptanceStep"), 0.0);
      EXPECT_TRUE(testing::bit_identical(batch.policy.mean_net().parameters(), theta_old));
    } else {
      EXPECT_GT(result.value("Misc/Nu_star"), 0.0);
      EXPECT_GT(result.value("Misc/AcceptanceStep"), 0.0);
      testing::expect_passes_constrained_tests(batch, before, c, config.trust_region.target_kl);
      EXPECT_LT(batch.cost_surrogate(), before.cost_surrogate);
    }
  }
}

TEST(Cpo, RejectedLineSearchLeavesParametersBitIdentical) {
  SyntheticBatch batch(64, 3, 4);
  RunConfig config = testing::config_for(Algorithm::cpo);
  config.trust_region.kl_accept_factor = 1e-30;
  config.trust_region.backtrack_budget = 2;
  const Eigen::VectorXd theta_old = batch.policy.mean_net().parameters();
  PolicySurrogate surrogate = batch.surrogate();
  Cpo cpo(config);
  const PolicyUpdateResult result = cpo.update(testing::inputs_for(batch, surrogate, 10.0, 100.0));
  EXPECT_EQ(result.value("Misc/AcceptanceStep"), 0.0);
  EXPECT_TRUE(testing::bit_identical(batch.policy.mean_net().parameters(), theta_old));
  EXPECT_THROW(cpo.update(testing::inputs_for(batch, surrogate, std::nan(""), 100.0)), std::invalid_argument);
  EXPECT_TRUE(cpo.state().empty());
}

}  // namespace
}  // namespace bsg::algos
