// max_grad_norm (PyTorch's clip_grad_norm_ as OmniSafe applies it): the rescaling on hand-computed
// vectors, and in the off-policy step the twin reward critics rescaled together and each cost
// critic alone before their first Adam steps, against the gradients of the public loss pieces and
// Adam's first-step formula written out here.
#include "algos/core/gradient_norm_clipping.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "../../common/finite_differences.h"
#include "../../common/random_matrices.h"
#include "algos/off_policy/make_off_policy_learner.h"
#include "algos/off_policy/off_policy_learner.h"
#include "common/mpi_context.h"

namespace bsg::algos {
namespace {

using testing::relative_error;

TEST(GradientNormClipping, RescalesToTheLimitOnlyAboveIt) {
  Eigen::VectorXd g = Eigen::Vector2d(3.0, 4.0);
  EXPECT_EQ(clip_gradient_norm(g, 10.0), 5.0);
  EXPECT_EQ(g, Eigen::VectorXd(Eigen::Vector2d(3.0, 4.0)));
  EXPECT_EQ(clip_gradient_norm(g, 0.0), 5.0);  // 0: never
  EXPECT_EQ(g, Eigen::VectorXd(Eigen::Vector2d(3.0, 4.0)));
  EXPECT_EQ(clip_gradient_norm(g, 1.0), 5.0);
  EXPECT_NEAR(g(0), 0.6, 1e-15);
  EXPECT_NEAR(g(1), 0.8, 1e-15);
}

TEST(GradientNormClipping, SeveralVectorsShareOneNorm) {
  Eigen::VectorXd a = Eigen::VectorXd::Constant(1, 3.0);
  Eigen::VectorXd b = Eigen::Vector3d(0.0, 4.0, 0.0);
  Eigen::VectorXd* both[] = {&a, &b};
  EXPECT_EQ(clip_gradient_norm(both, 2.5), 5.0);
  EXPECT_NEAR(a(0), 1.5, 1e-15);
  EXPECT_NEAR(b(1), 2.0, 1e-15);
  EXPECT_EQ(b(0), 0.0);
}

constexpr int kObs = 3, kAct = 2, kRows = 9;

using testing::uniform_matrix;

// Adam's first step from zero moments: m^ = g, v^ = g^2, so theta -= lr g / (|g| + eps).
Eigen::VectorXd first_adam_step(const Eigen::VectorXd& gradient, double learning_rate) {
  return -learning_rate * gradient.array() / (gradient.array().abs() + 1e-8);
}

TEST(OffPolicyGradientClipping, TwinCriticsTogetherAndEachCostCriticAloneBeforeTheirAdamSteps) {
  RunConfig config;
  config.alg = Algorithm::sac_lag;
  config.hidden_sizes = {6, 5};
  config.dtype = Dtype::float64;
  config.off_policy.critic_lr = 1e-3;
  // Small enough that every clipped entry is near Adam's epsilon, where the step shows the scale.
  config.first_order.max_grad_norm = 1e-7;
  Rng init_rng(3);
  Rng probe_init_rng = init_rng;  // the same networks
  const auto owned_learner = make_off_policy_learner(config, kObs, kAct, 1, init_rng);
  const auto owned_probe = make_off_policy_learner(config, kObs, kAct, 1, probe_init_rng);
  OffPolicyLearner& learner = *owned_learner;
  OffPolicyLearner& probe = *owned_probe;
  Rng batch_rng(4);
  ReplayBatch batch;
  batch.observations = uniform_matrix(kRows, kObs, 1.0, batch_rng);
  batch.actions = uniform_matrix(kRows, kAct, 1.0, batch_rng);
  batch.rewards = uniform_matrix(kRows, 1, 1.0, batch_rng);
  batch.costs = uniform_matrix(kRows, 1, 1.0, batch_rng).cwiseAbs();
  batch.next_observations = uniform_matrix(kRows, kObs, 1.0, batch_rng);
  batch.discounts = Eigen::VectorXd::Constant(kRows, 0.97);
  batch.terminals = Eigen::VectorXd::Zero(kRows);

  // The unclipped gradients: the step's first draws are eps for a' ~ pi(.|s'), column by column.
  Rng step_rng(5);
  Rng noise_rng = step_rng;
  Eigen::MatrixXd next_noise(kRows, kAct);
  for (Eigen::Index j = 0; j < kAct; ++j) {
    for (Eigen::Index i = 0; i < kRows; ++i) next_noise(i, j) = standard_normal(noise_rng);
  }
  probe.compute_targets(batch, next_noise);
  const Eigen::VectorXd reward_targets = probe.reward_targets();
  const Eigen::VectorXd cost_targets = probe.cost_targets().col(0);
  std::vector<Eigen::VectorXd> reward_gradients(2);
  double squared_norm = 0.0;
  for (int k = 0; k < 2; ++k) {
    reward_gradients[k].resize(probe.reward_critic(k).num_parameters());
    probe.critic_loss(probe.reward_critic(k), batch, reward_targets, reward_gradients[k]);
    squared_norm += reward_gradients[k].squaredNorm();
  }
  Eigen::VectorXd cost_gradient(probe.cost_critic(0).num_parameters());
  probe.critic_loss(probe.cost_critic(0), batch, cost_targets, cost_gradient);
  const double twin_scale = config.first_order.max_grad_norm / std::sqrt(squared_norm);
  const double cost_scale = config.first_order.max_grad_norm / cost_gradient.norm();
  ASSERT_LT(twin_scale, 1e-3);
  ASSERT_LT(cost_scale, 1e-3);

  const std::vector<double> lambdas{0.5};
  learner.update(batch, lambdas, step_rng, MpiContext::single_process());
  for (int k = 0; k < 2; ++k) {
    const Eigen::VectorXd moved = learner.reward_critic(k).parameters() - probe.reward_critic(k).parameters();
    EXPECT_LT(relative_error(moved, first_adam_step(twin_scale * reward_gradients[k], config.off_policy.critic_lr)), 1e-8)
        << "reward critic " << k;
  }
  const Eigen::VectorXd moved = learner.cost_critic(0).parameters() - probe.cost_critic(0).parameters();
  EXPECT_LT(relative_error(moved, first_adam_step(cost_scale * cost_gradient, config.off_policy.critic_lr)), 1e-8);
}

}  // namespace
}  // namespace bsg::algos
