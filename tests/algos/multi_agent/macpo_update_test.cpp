// MACPO's agent step (algos/multi_agent/macpo_update.h) on a 2-parameter linear Gaussian agent
// after another agent's hand-set step: its full step against the optimum of CPO's linearised
// problem for the corrected surrogates, found independently on the trust region's ellipse (and
// the recovery step along -F^-1 b); SafePO's constraint value; with one agent, CPO bit for bit.
#include "algos/multi_agent/macpo_update.h"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "../algorithm_test_support.h"
#include "algos/trust_region/trust_region_steps.h"
#include "sequential_test_support.h"

namespace bsg::algos {
namespace {
namespace macpo_update_test {

using testing::vector_of;

constexpr double kTargetKl = 0.01;

RunConfig macpo_config() {
  RunConfig config = testing::config_for(Algorithm::cpo);
  config.trust_region.target_kl = kTargetKl;
  config.trust_region.cg_damping = 0.0;      // F is then the mean KL's Hessian itself
  config.trust_region.fvp_subsample = 1;     // over every sample
  config.trust_region.cpo_r_sign = CpoRSign::corrected;  // SafePO's r = -g^T F^-1 b
  return config;
}

// Agent 0 (1 -> 1) moves by hand; agent 1 (1 -> 1, mu = w o + b) takes MACPO's step. Its
// advantages are large enough (|g|, |b| of order 1) that conjugate gradient's 1e-6 in its
// denominators (docs/algorithms.md#conjugate-gradient, Q9) moves the step by less than 1e-6 of it.
struct TwoAgents {
  double sigma_0 = 0.4, sigma_1 = 0.5;
  Eigen::VectorXd theta_0 = vector_of({0.5, 0.1}), theta_0_new = vector_of({0.45, 0.18});
  Eigen::VectorXd theta_1 = vector_of({0.3, -0.2});
  std::vector<GaussianPolicy> policies;
  std::vector<AgentBatch> batches;

  TwoAgents() {
    policies.push_back(testing::linear_policy(1, 1, theta_0, sigma_0));
    policies.push_back(testing::linear_policy(1, 1, theta_1, sigma_1));
    batches.push_back(testing::linear_batch(vector_of({0.2, -0.7, 1.0, 0.1, -0.3, 0.8}), 1, theta_0, sigma_0,
                                            vector_of({-0.4, 0.9, 0.3, -1.2, 0.5, 1.0}), Eigen::VectorXd::Zero(6),
                                            Eigen::VectorXd::Zero(6)));
    batches.push_back(testing::linear_batch(vector_of({-1.0, -0.5, 0.0, 0.5, 1.0, 1.5}), 1, theta_1, sigma_1,
                                            vector_of({0.7, -1.1, 0.4, 1.3, -0.6, 0.2}),
                                            10.0 * vector_of({1.0, -0.5, 0.3, 0.8, -1.2, 0.6}),
                                            10.0 * vector_of({0.9, 0.2, -0.4, 1.1, 0.5, -0.3})));
  }

  // Runs order {0, 1}: agent 0 to theta_0_new by hand, agent 1 MACPO's step with c.
  MacpoAgentStep run(double c) {
    MacpoAgentStep step;
    const std::vector<int> order{0, 1};
    const AgentUpdate update = [&](int agent, const CorrectionFactor& factor) {
      if (agent == 0) {
        policies[0].mean_net().set_parameters(theta_0_new);
        return std::vector<NamedScalar>{};
      }
      step = macpo_agent_step(policies[1], batches[1], factor, c, macpo_config(), testing::single_process());
      return step.diagnostics;
    };
    sequential_round(testing::pointers_to(policies), batches, order, update);
    return step;
  }

  // The linearised problem of agent 1 at theta_1, written out: M from agent 0's hand ratios,
  // g = 1/N sum M A (a - mu) / sigma^2 [o, 1], b alike with A^C, F = 1/(N sigma^2) sum [o, 1][o, 1]^T.
  struct Problem {
    Eigen::Vector2d g, b;
    Eigen::Matrix2d F;
  };
  Problem problem() const {
    const Eigen::VectorXd m = testing::linear_ratios(batches[0], theta_0, theta_0_new, sigma_0);
    const AgentBatch& batch = batches[1];
    const Eigen::MatrixXd means = testing::linear_means(batch.observations, 1, theta_1);
    Problem p;
    p.g.setZero();
    p.b.setZero();
    p.F.setZero();
    const double n = 6.0;
    for (Eigen::Index i = 0; i < 6; ++i) {
      const Eigen::Vector2d jacobian(batch.observations(i, 0), 1.0);
      const double score = (batch.actions(i, 0) - means(i, 0)) / (sigma_1 * sigma_1);
      p.g += m[i] * batch.advantages[i] * score * jacobian / n;
      p.b += m[i] * batch.cost_advantages[i] * score * jacobian / n;
      p.F += jacobian * jacobian.transpose() / (n * sigma_1 * sigma_1);
    }
    return p;
  }
};

// max g^T x  s.t.  c + b^T x <= 0,  1/2 x^T F x <= delta, for a problem whose constraint cuts the
// trust region: the optimum of a linear objective over the ellipse cut by a half-plane is the
// ellipse's own maximiser if feasible, else one of the two points where the line meets the
// ellipse. With F = L L^T and x = sqrt(2 delta) L^-T z, |z| = 1, these are found in closed form.
Eigen::Vector2d ellipse_optimum(const Eigen::Vector2d& g, const Eigen::Vector2d& b, const Eigen::Matrix2d& F,
                                double c, double delta) {
  const Eigen::Matrix2d L = F.llt().matrixL();
  const Eigen::Matrix2d L_inverse = L.inverse();
  const double radius = std::sqrt(2.0 * delta);
  const Eigen::Vector2d g_z = L_inverse * g;  // g^T x = radius g_z^T z
  const Eigen::Vector2d b_z = L_inverse * b;  // b^T x = radius b_z^T z
  const auto x_of = [&](const Eigen::Vector2d& z) { return Eigen::Vector2d(radius * L_inverse.transpose() * z); };
  const Eigen::Vector2d best = g_z.normalized();
  if (c + radius * b_z.dot(best) <= 0.0) return x_of(best);
  const double kappa = -c / radius;  // b_z^T z = kappa on the line
  const Eigen::Vector2d along = b_z * kappa / b_z.squaredNorm();
  const Eigen::Vector2d normal = Eigen::Vector2d(-b_z[1], b_z[0]).normalized();
  const double tau = std::sqrt(1.0 - kappa * kappa / b_z.squaredNorm());
  const Eigen::Vector2d z_plus = along + tau * normal, z_minus = along - tau * normal;
  return g_z.dot(z_plus) >= g_z.dot(z_minus) ? x_of(z_plus) : x_of(z_minus);
}

class MacpoAgentStepOracle : public ::testing::TestWithParam<std::pair<double, CpoCase>> {};

TEST_P(MacpoAgentStepOracle, IsCposOptimumForTheCorrectedSurrogates) {
  const auto [c, expected_case] = GetParam();
  TwoAgents agents;
  const MacpoAgentStep step = agents.run(c);
  const TwoAgents::Problem p = agents.problem();
  ASSERT_EQ(step.update.step.optim_case, expected_case);
  EXPECT_LT((step.update.gradients.reward - p.g).norm(), 1e-14);
  EXPECT_LT((step.update.gradients.cost - p.b).norm(), 1e-14);

  const Eigen::Vector2d expected = ellipse_optimum(p.g, p.b, p.F, c, kTargetKl);
  EXPECT_LT((step.update.step.full_step - expected).norm(), 1e-6 * expected.norm())
      << step.update.step.full_step.transpose() << " vs " << expected.transpose();
  // The line search's accepted step is a power of the decay of that step on agent 1 alone.
  const int accepted = step.update.search.acceptance_step;
  ASSERT_GT(accepted, 0);
  const Eigen::VectorXd theta = agents.theta_1 + std::pow(0.8, accepted - 1) * step.update.step.full_step;
  EXPECT_LT((agents.policies[1].mean_net().parameters() - theta).norm(), 1e-15);
  EXPECT_EQ(agents.policies[0].mean_net().parameters(), agents.theta_0_new);
}

// c = -0.1: feasible, the TRPO step would break the linearised constraint (case 2);
// c = 0.1: infeasible, a step within the trust region satisfies it (case 1).
INSTANTIATE_TEST_SUITE_P(ConstraintCutsTheTrustRegion, MacpoAgentStepOracle,
                         ::testing::Values(std::pair{-0.1, CpoCase::constraint_cuts_region},
                                           std::pair{0.1, CpoCase::feasible_recovery}));

TEST(MacpoAgentStep, RecoveryDescendsTheCorrectedCostToTheTrustRegionsEdge) {
  TwoAgents agents;
  const double c = 5.0;  // no step in the trust region reaches c + b^T x <= 0 (case 0)
  const MacpoAgentStep step = agents.run(c);
  ASSERT_EQ(step.update.step.optim_case, CpoCase::infeasible_recovery);
  const TwoAgents::Problem p = agents.problem();
  // The step that lowers b^T x most with 1/2 x^T F x = delta: -sqrt(2 delta / b^T F^-1 b) F^-1 b.
  const Eigen::Vector2d natural = p.F.inverse() * p.b;
  const Eigen::Vector2d expected = -std::sqrt(2.0 * kTargetKl / p.b.dot(natural)) * natural;
  EXPECT_LT((step.update.step.full_step - expected).norm(), 1e-6 * expected.norm());
}

TEST(MacpoConstraintViolation, IsSafePosDiscountedGap) {
  EXPECT_NEAR(macpo_constraint_violation(30.0, 25.0, 0.99), 5.0 * 0.01, 1e-15);
  EXPECT_NEAR(macpo_constraint_violation(10.0, 25.0, 0.96), -15.0 * 0.04, 1e-15);
  EXPECT_EQ(macpo_constraint_violation(25.0, 25.0, 0.99), 1e-8);
  EXPECT_THROW(macpo_constraint_violation(std::nan(""), 25.0, 0.99), std::invalid_argument);
  EXPECT_THROW(macpo_constraint_violation(30.0, 25.0, 1.5), std::invalid_argument);
}

TEST(MacpoWithOneAgent, IsCposStepBitForBit) {
  for (const double mean_episode_cost : {10.0, 40.0}) {
    const RunConfig config = testing::config_for(Algorithm::cpo);
    testing::SyntheticBatch reference(64, 3, 4);
    PolicySurrogate surrogate = reference.surrogate();
    Cpo cpo(config);
    const PolicyUpdateResult expected =
        cpo.update(testing::inputs_for(reference, surrogate, mean_episode_cost, 100.0));

    testing::SyntheticBatch synthetic(64, 3, 4);
    std::vector<GaussianPolicy> policies{synthetic.policy};
    const std::vector<AgentBatch> batches{{synthetic.observations, synthetic.actions, synthetic.old_log_probs,
                                           synthetic.advantages, synthetic.cost_advantages}};
    const std::vector<int> order{0};
    const std::vector<double> c{per_step_constraint_violation(mean_episode_cost, 100.0, config.cost_limit)};
    const std::vector<AgentRoundStatistics> statistics =
        macpo_round(testing::pointers_to(policies), batches, order, c, config, testing::single_process());
    ASSERT_EQ(statistics.size(), 1u);
    EXPECT_TRUE(
        testing::bit_identical(policies[0].mean_net().parameters(), reference.policy.mean_net().parameters()));
    EXPECT_EQ(statistics[0].diagnostics, expected.diagnostics);
    EXPECT_GT(statistics[0].step_norm, 0.0);
  }
}

TEST(MacpoRound, RefusesAMiscountOfConstraintValues) {
  TwoAgents agents;
  const std::vector<int> order{1, 0};
  const std::vector<double> one_c{0.1};
  const std::vector<GaussianPolicy*> policies = testing::pointers_to(agents.policies);
  EXPECT_THROW(macpo_round(policies, agents.batches, order, one_c, macpo_config(), testing::single_process()),
               std::invalid_argument);
}

}  // namespace macpo_update_test
}  // namespace
}  // namespace bsg::algos
