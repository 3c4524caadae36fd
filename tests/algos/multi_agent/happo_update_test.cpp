// HAPPO's agent update (algos/multi_agent/happo_update.h): its loss against
// -1/N sum_i M_i min(rho_i A_i, clip(rho_i) A_i) written out for a linear Gaussian policy, its
// gradient against central differences, and with one agent PPO's loss and update bit for bit.
#include "algos/multi_agent/happo_update.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "../algorithm_test_support.h"
#include "algos/first_order/first_order_update.h"
#include "algos/multi_agent/sequential_order.h"
#include "sequential_test_support.h"

namespace bsg::algos {
namespace {
namespace happo_update_test {

using testing::vector_of;

// A 1 -> 1 linear agent at theta_old, then moved so that some ratios leave [0.8, 1.2].
struct LinearAgent {
  double sigma = 0.4;
  Eigen::VectorXd theta_old = vector_of({0.5, -0.1});
  Eigen::VectorXd theta = vector_of({0.8, 0.1});
  AgentBatch batch;
  GaussianPolicy policy;

  LinearAgent()
      : batch(testing::linear_batch(vector_of({-1.5, -0.5, 0.0, 0.4, 1.0, 2.0}), 1, vector_of({0.5, -0.1}), 0.4,
                                    vector_of({0.3, -1.2, 0.8, 0.1, -0.4, 1.5}),
                                    vector_of({1.0, -0.7, 0.4, -1.3, 0.9, 0.2}), Eigen::VectorXd::Zero(6))),
        policy(testing::linear_policy(1, 1, vector_of({0.8, 0.1}), 0.4)) {}
};

TEST(HappoClippedLoss, IsTheCorrectedClippedSurrogateWrittenOut) {
  LinearAgent agent;
  CorrectionFactor factor(6);
  const Eigen::VectorXd log_m = vector_of({0.3, -0.2, 0.0, 0.5, -0.6, 0.1});
  factor.include_agent(log_m, Eigen::VectorXd::Zero(6));
  const double clip = 0.2;

  const Eigen::VectorXd rho = testing::linear_ratios(agent.batch, agent.theta_old, agent.theta, agent.sigma);
  double expected = 0.0;
  int clipped = 0;
  for (Eigen::Index i = 0; i < 6; ++i) {
    const double m = std::exp(log_m[i]);
    const double a = agent.batch.advantages[i];
    const double clipped_rho = std::min(std::max(rho[i], 1.0 - clip), 1.0 + clip);
    expected -= m * std::min(rho[i] * a, clipped_rho * a) / 6.0;
    clipped += rho[i] * a > clipped_rho * a ? 1 : 0;
  }
  ASSERT_GE(clipped, 1);  // the clip holds some samples
  EXPECT_NEAR(happo_clipped_loss(agent.policy, agent.batch, factor, clip), expected, 1e-14);
}

TEST(HappoClippedLoss, GradientMatchesCentralDifferences) {
  testing::SyntheticBatch synthetic(48, 21, 22);
  AgentBatch batch{synthetic.observations, synthetic.actions, synthetic.old_log_probs, synthetic.advantages,
                   synthetic.cost_advantages};
  // Move the policy off theta_old so that ratios differ from 1 and some are clipped.
  Eigen::VectorXd theta = synthetic.policy.mean_net().parameters();
  Rng rng(3);
  for (Eigen::Index k = 0; k < theta.size(); ++k) theta[k] += 0.05 * standard_normal(rng);
  synthetic.policy.mean_net().set_parameters(theta);
  CorrectionFactor factor(48);
  Eigen::VectorXd log_m(48);
  for (Eigen::Index i = 0; i < 48; ++i) log_m[i] = 0.3 * standard_normal(rng);
  factor.include_agent(log_m, Eigen::VectorXd::Zero(48));

  Eigen::VectorXd gradient;
  happo_clipped_loss(synthetic.policy, batch, factor, 0.2, &gradient);
  const Eigen::VectorXd numeric = testing::central_difference_gradient(
      synthetic, [&] { return happo_clipped_loss(synthetic.policy, batch, factor, 0.2); });
  ASSERT_EQ(gradient.size(), numeric.size());
  EXPECT_LT((gradient - numeric).cwiseAbs().maxCoeff(), 1e-7);
  EXPECT_GT(gradient.norm(), 1e-3);
}

TEST(HappoWithOneAgent, IsPpoBitForBit) {
  testing::SyntheticBatch synthetic(64, 31, 32);
  AgentBatch batch{synthetic.observations, synthetic.actions, synthetic.old_log_probs, synthetic.advantages,
                   synthetic.cost_advantages};
  // The loss: PPO's clipped loss on A with M = 1.
  {
    const CorrectionFactor factor(64);
    PolicySurrogate surrogate = synthetic.surrogate();
    const Eigen::MatrixXd anchor = policy_means(synthetic.policy, synthetic.observations);
    SampleLossBatch losses(surrogate, anchor);
    const std::vector<Eigen::Index> rows = testing::all_rows(64);
    Eigen::VectorXd ppo_gradient, happo_gradient;
    const double ppo_loss = losses.loss(synthetic.policy, rows, clipped_surrogate_loss(synthetic.advantages, 0.2),
                                        &ppo_gradient);
    EXPECT_EQ(happo_clipped_loss(synthetic.policy, batch, factor, 0.2, &happo_gradient), ppo_loss);
    EXPECT_TRUE(testing::bit_identical(happo_gradient, ppo_gradient));
  }
  // The update: a HAPPO round of one agent takes the PPO update's step.
  const RunConfig config = testing::config_for(Algorithm::ppo);
  testing::SyntheticBatch reference(64, 31, 32);
  PolicySurrogate surrogate = reference.surrogate();
  Ppo reference_ppo(config);
  Rng reference_rng(9);
  const PolicyUpdateInputs inputs{reference.policy, surrogate, 0.0, 0.0, testing::single_process(), {},
                                  &reference_rng};
  const PolicyUpdateResult expected = reference_ppo.update(inputs);

  std::vector<GaussianPolicy> policies{synthetic.policy};
  Ppo ppo(config);
  std::vector<Ppo*> ppos{&ppo};
  const std::vector<AgentBatch> batches{batch};
  Rng rng(9);
  const std::vector<int> order = sequential_agent_order(1, 0, 0);
  const std::vector<AgentRoundStatistics> statistics =
      happo_round(testing::pointers_to(policies), ppos, batches, order, testing::single_process(), rng);
  ASSERT_EQ(statistics.size(), 1u);
  EXPECT_TRUE(testing::bit_identical(policies[0].mean_net().parameters(), reference.policy.mean_net().parameters()));
  EXPECT_EQ(statistics[0].diagnostics, expected.diagnostics);
  EXPECT_GT(statistics[0].step_norm, 0.0);
}

TEST(HappoRound, RefusesAMissingOrMiscountedPpo) {
  LinearAgent agent;
  std::vector<GaussianPolicy> policies{agent.policy};
  const std::vector<AgentBatch> batches{agent.batch};
  const std::vector<int> order{0};
  Rng rng(1);
  const auto round_with = [&](const std::vector<Ppo*>& ppos) {
    happo_round(testing::pointers_to(policies), ppos, batches, order, testing::single_process(), rng);
  };
  EXPECT_THROW(round_with({}), std::invalid_argument);
  EXPECT_THROW(round_with({nullptr}), std::invalid_argument);
  AgentBatch short_batch = agent.batch;
  short_batch.old_log_probs = Eigen::VectorXd::Zero(2);
  EXPECT_THROW(happo_clipped_loss(agent.policy, short_batch, CorrectionFactor(6), 0.2), std::invalid_argument);
}

}  // namespace happo_update_test
}  // namespace
}  // namespace bsg::algos
