// Surrogates and their gradients g and b (docs/algorithms.md#surrogates-and-gradients) against central
// finite differences, and the ratio/KL at theta_old.
#include "algos/core/policy_surrogate.h"

#include <gtest/gtest.h>

#include <stdexcept>

#include "../../common/finite_differences.h"

namespace bsg::algos {
namespace {

using testing::finite_difference_gradient;
using testing::relative_error;

struct Batch {
  Rng rng{21};
  GaussianPolicy policy{4, 2, {6, 5}, rng};
  Eigen::MatrixXd observations, actions;
  Eigen::VectorXd old_log_probs, advantages, cost_advantages;

  explicit Batch(Eigen::Index n) : observations(n, 4), actions(n, 2), old_log_probs(n), advantages(n), cost_advantages(n) {
    policy.set_std(0.4);
    MlpSampleWorkspace workspace;
    for (Eigen::Index i = 0; i < n; ++i) {
      for (int j = 0; j < 4; ++j) observations(i, j) = standard_normal(rng);
      Eigen::VectorXd action(2);
      old_log_probs[i] = policy.sample_action(observations.row(i).transpose(), action, rng, workspace);
      actions.row(i) = action.transpose();
      advantages[i] = standard_normal(rng);
      cost_advantages[i] = uniform(rng, 0.0, 2.0);
    }
  }
  PolicySurrogate surrogate() const {
    return PolicySurrogate(observations, actions, old_log_probs, advantages, cost_advantages);
  }
};

TEST(PolicySurrogate, RatioIsOneAndKlZeroAtThetaOld) {
  Batch batch(40);
  PolicySurrogate surrogate = batch.surrogate();
  surrogate.set_reference_means(batch.policy);
  const SurrogateValues values = surrogate.evaluate(batch.policy);
  EXPECT_NEAR(values.mean_ratio, 1.0, 1e-12);
  EXPECT_NEAR(values.reward_surrogate, batch.advantages.mean(), 1e-12);
  EXPECT_NEAR(values.cost_surrogate, batch.cost_advantages.mean(), 1e-12);
  EXPECT_EQ(values.kl, 0.0);
}

TEST(PolicySurrogate, GradientsGAndBMatchCentralFiniteDifferences) {
  Batch batch(30);
  // Move away from theta_old so that the ratios differ from 1.
  Eigen::VectorXd theta = batch.policy.mean_net().parameters();
  for (Eigen::Index k = 0; k < theta.size(); ++k) theta[k] += 0.05 * standard_normal(batch.rng);
  batch.policy.mean_net().set_parameters(theta);
  PolicySurrogate surrogate = batch.surrogate();
  GaussianPolicy probe = batch.policy;
  const auto reward = [&](const Eigen::VectorXd& t) {
    probe.mean_net().set_parameters(t);
    return surrogate.evaluate(probe).reward_surrogate;
  };
  const auto cost = [&](const Eigen::VectorXd& t) {
    probe.mean_net().set_parameters(t);
    return surrogate.evaluate(probe).cost_surrogate;
  };
  Eigen::VectorXd g(theta.size()), b(theta.size()), mixed(theta.size());
  surrogate.gradient(batch.policy, 1.0, 0.0, g);
  surrogate.gradient(batch.policy, 0.0, 1.0, b);
  surrogate.gradient(batch.policy, 0.5, -2.0, mixed);
  const Eigen::VectorXd g_fd = finite_difference_gradient(reward, theta, 1e-6);
  const Eigen::VectorXd b_fd = finite_difference_gradient(cost, theta, 1e-6);
  EXPECT_LT(relative_error(g, g_fd), 1e-6);
  EXPECT_LT(relative_error(b, b_fd), 1e-6);
  EXPECT_LT(relative_error(mixed, 0.5 * g - 2.0 * b), 1e-13);
}

TEST(PolicySurrogate, KlAgainstReferenceMeansMatchesThePolicyFormula) {
  Batch batch(12);
  PolicySurrogate surrogate = batch.surrogate();
  surrogate.set_reference_means(batch.policy);
  const Eigen::MatrixXd old_means = surrogate.reference_means();
  batch.policy.mean_net().set_parameters(batch.policy.mean_net().parameters() * 1.1);
  const SurrogateValues values = surrogate.evaluate(batch.policy);
  MlpBatchWorkspace workspace;
  const Eigen::MatrixXd new_means = batch.policy.mean_net().forward_batch(batch.observations, workspace);
  EXPECT_NEAR(values.kl, (old_means - new_means).squaredNorm() / (2 * 0.16) / (12 * 2), 1e-15);
  EXPECT_GT(values.kl, 0.0);
}

TEST(PolicySurrogate, BadInputGivesExceptions) {
  Batch batch(5);
  EXPECT_THROW(PolicySurrogate(batch.observations, batch.actions.topRows(4), batch.old_log_probs, batch.advantages,
                               batch.cost_advantages),
               std::invalid_argument);
  PolicySurrogate surrogate = batch.surrogate();
  Rng rng(1);
  const GaussianPolicy other(3, 2, {4}, rng);
  EXPECT_THROW(surrogate.evaluate(other), std::invalid_argument);
  Eigen::VectorXd wrong(7);
  EXPECT_THROW(surrogate.gradient(batch.policy, 1.0, 0.0, wrong), std::invalid_argument);
}

}  // namespace
}  // namespace bsg::algos
