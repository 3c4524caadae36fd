// The learned log sigma of the first-order algorithms (docs/algorithms.md#learned-log-sigma):
// the losses' gradients with respect to [theta, s] against central finite
// differences of hand-written losses (per-dimension Gaussian log-probability and
// the Gaussian KL with both sigmas written out), a PPO update on a tiny batch
// against the Adam steps computed by hand on (w, b, s), and a run stopped and
// resumed from its checkpoint against an uninterrupted one.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <memory>
#include <numbers>
#include <numeric>
#include <string>
#include <vector>

#include "../../test_support.h"
#include "../algorithm_test_support.h"
#include "algos/first_order/cup.h"
#include "algos/first_order/first_order_update.h"
#include "algos/first_order/focops.h"
#include "algos/first_order/ppo.h"
#include "algos/training/on_policy_trainer.h"
#include "../scripted_env.h"

namespace bsg::algos {
namespace {

using testing::SyntheticBatch;
using testing::all_rows;
using testing::HandAdam;

const double kHalfLog2Pi = 0.5 * std::log(2.0 * std::numbers::pi);

// Hand-written log pi(a_i|s_i) = sum_j -1/2 ((a_ij - mu_ij) / sigma_j)^2 - log sigma_j - 1/2 log 2 pi.
Eigen::VectorXd hand_ratios(const SyntheticBatch& batch, const Eigen::VectorXd& s) {
  const Eigen::MatrixXd mu = batch.means();
  Eigen::VectorXd rho(mu.rows());
  for (Eigen::Index i = 0; i < mu.rows(); ++i) {
    double log_prob = 0;
    for (Eigen::Index j = 0; j < mu.cols(); ++j) {
      const double z = (batch.actions(i, j) - mu(i, j)) / std::exp(s[j]);
      log_prob += -0.5 * z * z - s[j] - kHalfLog2Pi;
    }
    rho[i] = std::exp(log_prob - batch.old_log_probs[i]);
  }
  return rho;
}

// KL(N(mu, sigma^2) || N(mu_a, sigma_a^2)) = log(sigma_a / sigma) + (sigma^2 + (mu - mu_a)^2) / (2 sigma_a^2) - 1/2, summed over j.
Eigen::VectorXd hand_kls(const SyntheticBatch& batch, const Eigen::VectorXd& s, const Eigen::MatrixXd& anchor,
                         const Eigen::VectorXd& anchor_s) {
  const Eigen::MatrixXd mu = batch.means();
  Eigen::VectorXd kl = Eigen::VectorXd::Zero(mu.rows());
  for (Eigen::Index i = 0; i < mu.rows(); ++i) {
    for (Eigen::Index j = 0; j < mu.cols(); ++j) {
      const double sigma = std::exp(s[j]), sigma_a = std::exp(anchor_s[j]);
      const double d = mu(i, j) - anchor(i, j);
      kl[i] += std::log(sigma_a / sigma) + (sigma * sigma + d * d) / (2 * sigma_a * sigma_a) - 0.5;
    }
  }
  return kl;
}

// Central differences of `loss(s)` over [theta, s] at the policy's current parameters.
template <class Loss>
Eigen::VectorXd finite_difference_gradient(SyntheticBatch& batch, const Loss& loss) {
  const Eigen::VectorXd theta = batch.policy.mean_net().parameters();
  const Eigen::VectorXd s = batch.policy.log_stds();
  const Eigen::Index p = theta.size();
  Eigen::VectorXd gradient(p + s.size());
  const double h = 1e-6;
  for (Eigen::Index k = 0; k < p; ++k) {
    Eigen::VectorXd shifted = theta;
    shifted[k] += h;
    batch.policy.mean_net().set_parameters(shifted);
    const double up = loss(s);
    shifted[k] = theta[k] - h;
    batch.policy.mean_net().set_parameters(shifted);
    const double down = loss(s);
    gradient[k] = (up - down) / (2 * h);
  }
  batch.policy.mean_net().set_parameters(theta);
  for (Eigen::Index j = 0; j < s.size(); ++j) {
    Eigen::VectorXd shifted = s;
    shifted[j] += h;
    const double up = loss(shifted);
    shifted[j] = s[j] - h;
    gradient[p + j] = (up - loss(shifted)) / (2 * h);
  }
  return gradient;
}

// A batch drawn with sigma 0.4, then a policy with a learned log sigma moved away from it in theta and s.
struct LearnedBatch {
  SyntheticBatch batch;
  Eigen::MatrixXd anchor;
  Eigen::VectorXd anchor_s{{std::log(0.4), std::log(0.4)}};

  LearnedBatch(std::uint64_t policy_seed, std::uint64_t batch_seed) : batch(40, policy_seed, batch_seed) {
    anchor = batch.means();
    batch.policy.learn_log_std(0.4);
    batch.policy.set_log_stds(Eigen::Vector2d(std::log(0.45), std::log(0.33)));
    Rng rng(policy_seed + 100);
    const auto p = static_cast<int>(batch.policy.mean_net().num_parameters());
    batch.policy.mean_net().set_parameters(batch.policy.mean_net().parameters() + 0.03 * testing::random_vector(p, rng));
  }
};

TEST(LearnedLogStd, ClippedSurrogateGradientMatchesFiniteDifferences) {
  LearnedBatch b(3, 4);
  const double eps = 0.1;
  const auto hand_loss = [&](const Eigen::VectorXd& s) {
    const Eigen::VectorXd rho = hand_ratios(b.batch, s);
    double sum = 0;
    for (Eigen::Index i = 0; i < rho.size(); ++i) {
      const double a = b.batch.advantages[i];
      sum += -std::min(rho[i] * a, std::clamp(rho[i], 1 - eps, 1 + eps) * a);
    }
    return sum / static_cast<double>(rho.size());
  };
  const Eigen::VectorXd rho = hand_ratios(b.batch, b.batch.policy.log_stds());
  int clipped = 0;
  for (Eigen::Index i = 0; i < rho.size(); ++i) {
    ASSERT_GT(std::min(std::abs(rho[i] - (1 - eps)), std::abs(rho[i] - (1 + eps))), 1e-4) << i;
    clipped += (rho[i] > 1 + eps && b.batch.advantages[i] > 0) || (rho[i] < 1 - eps && b.batch.advantages[i] < 0);
  }
  ASSERT_GT(clipped, 2);  // both branches of the min are exercised
  ASSERT_LT(clipped, 38);
  PolicySurrogate surrogate = b.batch.surrogate();
  SampleLossBatch losses(surrogate, b.anchor, b.anchor_s);
  Eigen::VectorXd gradient;
  const double loss =
      losses.loss(b.batch.policy, all_rows(40), clipped_surrogate_loss(b.batch.advantages, eps), &gradient);
  EXPECT_NEAR(loss, hand_loss(b.batch.policy.log_stds()), 1e-12);
  const Eigen::VectorXd expected = finite_difference_gradient(b.batch, hand_loss);
  ASSERT_EQ(gradient.size(), expected.size());
  EXPECT_LT((gradient - expected).norm(), 1e-6 * expected.norm()) << gradient.transpose() << "\n" << expected.transpose();
  // The log sigma entries are not negligible next to the mean's.
  EXPECT_GT(gradient.tail(2).norm(), 1e-3);
  EXPECT_LT((gradient.tail(2) - expected.tail(2)).norm(), 1e-6 * expected.tail(2).norm());
}

TEST(LearnedLogStd, FocopsAndCupLossGradientsWithTheKlTermMatchFiniteDifferences) {
  LearnedBatch b(5, 6);
  const Eigen::VectorXd a = b.batch.advantages - 0.7 * b.batch.cost_advantages;
  const double eta = 1e9;  // FOCOPS's mask off here: its indicator is constant, so every sample counts
  const auto hand_focops = [&](const Eigen::VectorXd& s) {
    return (hand_kls(b.batch, s, b.anchor, b.anchor_s) - hand_ratios(b.batch, s).cwiseProduct(a) / 1.5).mean();
  };
  const auto hand_cup = [&](const Eigen::VectorXd& s) {
    return (hand_kls(b.batch, s, b.anchor, b.anchor_s) + hand_ratios(b.batch, s).cwiseProduct(a)).mean();
  };
  PolicySurrogate surrogate = b.batch.surrogate();
  SampleLossBatch losses(surrogate, b.anchor, b.anchor_s);
  Eigen::VectorXd gradient;
  EXPECT_NEAR(losses.loss(b.batch.policy, all_rows(40), focops_loss(a, 1.5, eta), &gradient),
              hand_focops(b.batch.policy.log_stds()), 1e-12);
  Eigen::VectorXd expected = finite_difference_gradient(b.batch, hand_focops);
  EXPECT_LT((gradient - expected).norm(), 1e-6 * expected.norm()) << gradient.transpose() << "\n" << expected.transpose();
  EXPECT_LT((gradient.tail(2) - expected.tail(2)).norm(), 1e-6 * expected.tail(2).norm());
  EXPECT_NEAR(losses.loss(b.batch.policy, all_rows(40), cup_projection_loss(a), &gradient),
              hand_cup(b.batch.policy.log_stds()), 1e-12);
  expected = finite_difference_gradient(b.batch, hand_cup);
  EXPECT_LT((gradient - expected).norm(), 1e-6 * expected.norm());
  // The KL early stop's mean KL is the hand-written Gaussian KL.
  EXPECT_NEAR(losses.mean_kl(b.batch.policy), hand_kls(b.batch, b.batch.policy.log_stds(), b.anchor, b.anchor_s).mean(),
              1e-13);
  // With the policy at its anchor the KL is zero (the sigma part included).
  const Eigen::MatrixXd own_means = b.batch.means();  // the batch keeps a reference: it must outlive it
  SampleLossBatch at_self(surrogate, own_means, b.batch.policy.log_stds());
  EXPECT_NEAR(at_self.mean_kl(b.batch.policy), 0.0, 1e-15);
}

TEST(LearnedLogStd, TheAnchorsSigmaKindMustMatchThePolicys) {
  LearnedBatch b(7, 8);
  PolicySurrogate surrogate = b.batch.surrogate();
  SampleLossBatch without_anchor_sigma(surrogate, b.anchor);
  EXPECT_THROW(without_anchor_sigma.mean_kl(b.batch.policy), std::invalid_argument);
  EXPECT_THROW(SampleLossBatch(surrogate, b.anchor, Eigen::VectorXd::Zero(3)), std::invalid_argument);
  EXPECT_THROW(b.batch.policy.set_std(0.3), std::invalid_argument);  // the trainer's annealing must not touch it
  EXPECT_THROW(b.batch.policy.set_log_stds(Eigen::Vector2d(0.0, std::nan(""))), std::invalid_argument);
  EXPECT_THROW(b.batch.policy.learn_log_std(0.0), std::invalid_argument);
  // The logged KL (mean over samples and dimensions of KL(old || new)) with both sigmas, written out.
  const Eigen::MatrixXd mu = b.batch.means();
  double kl_sum = 0;
  for (Eigen::Index i = 0; i < mu.rows(); ++i) {
    for (Eigen::Index j = 0; j < 2; ++j) {
      const double sigma = std::exp(b.batch.policy.log_stds()[j]), sigma_old = std::exp(b.anchor_s[j]);
      const double d = mu(i, j) - b.anchor(i, j);
      kl_sum += std::log(sigma / sigma_old) + (sigma_old * sigma_old + d * d) / (2 * sigma * sigma) - 0.5;
    }
  }
  EXPECT_NEAR(b.batch.policy.mean_kl(b.anchor, mu, b.anchor_s), kl_sum / static_cast<double>(mu.size()), 1e-14);
  // The logged sigma is the mean of the sigma_j; the entropy the mean per-dimension one.
  EXPECT_NEAR(b.batch.policy.std(), (0.45 + 0.33) / 2, 1e-15);
  EXPECT_NEAR(b.batch.policy.entropy_per_dimension(), 0.5 + kHalfLog2Pi + (std::log(0.45) + std::log(0.33)) / 2, 1e-15);
}

// ---------------------------------------------------------------------------
// PPO on a tiny batch: mu = w s + b (1 -> 1, no hidden layer), sigma = exp(s_log)
// learned from 0.5, two samples, one minibatch per pass, two passes.

TEST(LearnedLogStd, PpoTakesTheHandComputedAdamStepsOnMeanAndLogSigma) {
  const double obs[2] = {0.5, -1.0}, act[2] = {0.3, -0.2}, adv[2] = {1.0, -2.0};
  const double w0 = 0.2, b0 = -0.1, s0 = std::log(0.5);
  const auto log_prob = [&](int i, double w, double b, double s) {
    const double z = (act[i] - (w * obs[i] + b)) / std::exp(s);
    return -0.5 * z * z - s - kHalfLog2Pi;
  };
  Rng rng(1);
  GaussianPolicy policy(1, 1, {}, rng);
  policy.learn_log_std(0.5);
  policy.mean_net().set_parameters(Eigen::Vector2d(w0, b0));
  Eigen::VectorXd old_log_probs(2);
  for (int i = 0; i < 2; ++i) old_log_probs[i] = log_prob(i, w0, b0, s0);
  PolicySurrogate surrogate(Eigen::MatrixXd{{obs[0]}, {obs[1]}}, Eigen::MatrixXd{{act[0]}, {act[1]}}, old_log_probs,
                            Eigen::VectorXd{{adv[0], adv[1]}}, Eigen::MatrixXd{{0.5}, {1.5}});
  RunConfig config = testing::config_for(Algorithm::ppo);
  config.first_order.learn_log_std = true;
  config.first_order.actor_lr = 0.05;
  config.first_order.update_iters = 2;
  config.first_order.policy_minibatch_size = 64;
  config.first_order.kl_early_stop = false;
  config.first_order.max_grad_norm = 0.0;
  config.first_order.clip = 0.2;
  Ppo ppo(config);
  Rng shuffle(3);
  ppo.update(PolicyUpdateInputs{policy, surrogate, 0.0, 100.0, testing::single_process(), {}, &shuffle});

  // By hand: l_i = -min(rho_i A_i, clip(rho_i) A_i), d l_i / d rho_i = -A_i unless the clip holds;
  // d rho / d mu = rho (a - mu) / sigma^2, d rho / d s = rho ((a - mu)^2 / sigma^2 - 1); mean over the 2 samples.
  double w = w0, b = b0, s = s0;
  HandAdam adam_w, adam_b, adam_s;
  for (int pass = 0; pass < 2; ++pass) {
    double gw = 0, gb = 0, gs = 0;
    for (int i = 0; i < 2; ++i) {
      const double rho = std::exp(log_prob(i, w, b, s) - old_log_probs[i]);
      const bool held = (adv[i] > 0 && rho > 1.2) || (adv[i] < 0 && rho < 0.8);
      const double coef = held ? 0.0 : -adv[i];
      const double variance = std::exp(2 * s);
      const double deviation = act[i] - (w * obs[i] + b);
      const double d_mu = coef * rho * deviation / variance / 2;
      gw += d_mu * obs[i];
      gb += d_mu;
      gs += coef * rho * (deviation * deviation / variance - 1) / 2;
    }
    w += adam_w.step(gw, 0.05);
    b += adam_b.step(gb, 0.05);
    s += adam_s.step(gs, 0.05);
  }
  EXPECT_NEAR(policy.mean_net().parameters()[0], w, 1e-12);
  EXPECT_NEAR(policy.mean_net().parameters()[1], b, 1e-12);
  ASSERT_EQ(policy.log_stds().size(), 1);
  EXPECT_NEAR(policy.log_stds()[0], s, 1e-12);
  EXPECT_GT(std::abs(s - s0), 0.05);  // Adam's first steps move log sigma by about lr each
  // The Adam state holds the moments of [w, b, s]: 1 + 2 * 3 entries.
  EXPECT_EQ(ppo.state().size(), 7u);
}

// ---------------------------------------------------------------------------
// Kill and resume: the checkpoint holds log sigma and its Adam moments.

TEST(LearnedLogStd, ResumingContinuesWithTheSameNumbers) {
  for (const Algorithm alg : {Algorithm::ppo_lag, Algorithm::cup}) {
    SCOPED_TRACE(std::string(to_string(alg)));
    testing::TemporaryDirectory dir;
    RunConfig config;
    config.env_id = "Scripted-v0";
    config.alg = alg;
    config.use_cost_value_function = true;
    config.hidden_sizes = {16, 16};
    config.epochs = 5;
    config.steps_per_epoch = 400;
    config.max_ep_len = 100;
    config.save_freq = 10;
    config.eval_episodes = 0;
    config.cost_limit = 5;
    config.first_order.update_iters = 3;
    config.first_order.policy_minibatch_size = 64;
    config.first_order.learn_log_std = true;
    config.first_order.learned_std_init = 0.6;
    OnPolicyTrainer whole(config, RunDirectory(dir.path() / "whole"), MpiContext::single_process(), {},
                          std::make_unique<testing::ScriptedEnv>(100));
    whole.run();
    TrainerOptions stop;
    stop.stop_after_epochs = 3;
    {
      OnPolicyTrainer first(config, RunDirectory(dir.path() / "split"), MpiContext::single_process(), stop,
                            std::make_unique<testing::ScriptedEnv>(100));
      EXPECT_EQ(first.run().epochs_completed, 3);
    }
    TrainerOptions resume;
    resume.resume = true;
    OnPolicyTrainer second(config, RunDirectory(dir.path() / "split"), MpiContext::single_process(), resume,
                           std::make_unique<testing::ScriptedEnv>(100));
    ASSERT_EQ(second.epochs_completed(), 3);
    second.run();
    const GaussianPolicy& learned = whole.actor_critic().policy;
    ASSERT_TRUE(learned.has_learned_std());
    EXPECT_NE(learned.log_stds()[0], std::log(0.6));  // it was trained
    EXPECT_EQ(second.actor_critic().policy.log_stds(), learned.log_stds());
    EXPECT_EQ(second.actor_critic().policy.mean_net().parameters(), learned.mean_net().parameters());
    EXPECT_EQ(second.algorithm().state(), whole.algorithm().state());
  }
}

}  // namespace
}  // namespace bsg::algos
