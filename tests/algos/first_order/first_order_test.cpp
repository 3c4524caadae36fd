// The first-order updates (docs/algorithms.md#first-order-updates): the losses
// of PPO, FOCOPS and CUP against hand-written losses, their gradients against
// central finite differences of those hand-written losses, and whole updates
// on a tiny hand-made batch against the step computed by hand (Adam's first
// steps on a linear policy), plus the Adam state's round trip.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <vector>

#include "../algorithm_test_support.h"
#include "algos/first_order/cup.h"
#include "algos/first_order/first_order_update.h"
#include "algos/first_order/focops.h"
#include "algos/first_order/ppo.h"

namespace bsg::algos {
namespace {

using testing::SyntheticBatch;
using testing::central_difference_gradient;
using testing::all_rows;
using testing::HandAdam;

// Hand-written per-sample KL(pi_theta || pi_anchor)[s_i], summed over action dimensions.
Eigen::VectorXd sample_kls(const SyntheticBatch& batch, const Eigen::MatrixXd& anchor) {
  const Eigen::MatrixXd mu = batch.means();
  const double sigma = batch.policy.std();
  Eigen::VectorXd kl(mu.rows());
  for (Eigen::Index i = 0; i < mu.rows(); ++i) kl[i] = (mu.row(i) - anchor.row(i)).squaredNorm() / (2 * sigma * sigma);
  return kl;
}

double hand_clipped_loss(const SyntheticBatch& batch, const Eigen::VectorXd& a, double eps) {
  const Eigen::VectorXd rho = batch.ratios();
  double sum = 0;
  for (Eigen::Index i = 0; i < rho.size(); ++i) {
    sum += -std::min(rho[i] * a[i], std::clamp(rho[i], 1 - eps, 1 + eps) * a[i]);
  }
  return sum / static_cast<double>(rho.size());
}

double hand_focops_loss(const SyntheticBatch& batch, const Eigen::MatrixXd& anchor, const Eigen::VectorXd& a,
                        double lambda, double eta) {
  const Eigen::VectorXd rho = batch.ratios();
  const Eigen::VectorXd kl = sample_kls(batch, anchor);
  double sum = 0;
  for (Eigen::Index i = 0; i < rho.size(); ++i) {
    if (kl[i] <= eta) sum += kl[i] - rho[i] * a[i] / lambda;
  }
  return sum / static_cast<double>(rho.size());
}

double hand_cup_loss(const SyntheticBatch& batch, const Eigen::MatrixXd& anchor, const Eigen::VectorXd& a) {
  return (sample_kls(batch, anchor) + batch.ratios().cwiseProduct(a)).mean();
}

// Moves the policy away from the one that drew the batch, so that ratios and KLs are not trivial.
Eigen::MatrixXd move_policy(SyntheticBatch& batch, double scale, std::uint64_t seed) {
  const Eigen::MatrixXd anchor = batch.means();
  Rng rng(seed);
  const Eigen::Index p = batch.policy.mean_net().num_parameters();
  batch.policy.mean_net().set_parameters(batch.policy.mean_net().parameters() + scale * testing::random_vector(static_cast<int>(p), rng));
  return anchor;
}

TEST(FirstOrderLosses, ClippedSurrogateMatchesTheHandWrittenLossAndFiniteDifferences) {
  SyntheticBatch batch(40, 3, 4);
  const Eigen::MatrixXd anchor = move_policy(batch, 0.05, 9);
  const double eps = 0.05;
  const Eigen::VectorXd rho = batch.ratios();
  int clipped = 0;
  for (Eigen::Index i = 0; i < rho.size(); ++i) {
    // No ratio sits on a kink of the min, where the difference quotient would straddle it.
    ASSERT_GT(std::min(std::abs(rho[i] - (1 - eps)), std::abs(rho[i] - (1 + eps))), 1e-4) << i;
    clipped += (rho[i] > 1 + eps && batch.advantages[i] > 0) || (rho[i] < 1 - eps && batch.advantages[i] < 0);
  }
  ASSERT_GT(clipped, 3);  // both branches are exercised
  ASSERT_LT(clipped, 37);
  PolicySurrogate surrogate = batch.surrogate();
  SampleLossBatch losses(surrogate, anchor);
  const std::vector<Eigen::Index> rows = all_rows(40);
  Eigen::VectorXd gradient;
  const double loss = losses.loss(batch.policy, rows, clipped_surrogate_loss(batch.advantages, eps), &gradient);
  EXPECT_NEAR(loss, hand_clipped_loss(batch, batch.advantages, eps), 1e-12);
  const Eigen::VectorXd expected = central_difference_gradient(batch, [&] { return hand_clipped_loss(batch, batch.advantages, eps); });
  EXPECT_LT((gradient - expected).norm(), 1e-6 * expected.norm()) << gradient.transpose() << "\n" << expected.transpose();
}

TEST(FirstOrderLosses, FocopsLossMatchesTheHandWrittenLossAndFiniteDifferences) {
  SyntheticBatch batch(40, 5, 6);
  const Eigen::MatrixXd anchor = move_policy(batch, 0.05, 11);
  const Eigen::VectorXd kl = sample_kls(batch, anchor);
  std::vector<double> sorted(kl.data(), kl.data() + kl.size());
  std::sort(sorted.begin(), sorted.end());
  const double eta = 0.5 * (sorted[20] + sorted[21]);  // half the samples masked
  for (double k : sorted) ASSERT_GT(std::abs(k - eta), 1e-6);
  const Eigen::VectorXd a = batch.advantages - 0.7 * batch.cost_advantages;  // A - nu A^C
  PolicySurrogate surrogate = batch.surrogate();
  SampleLossBatch losses(surrogate, anchor);
  Eigen::VectorXd gradient;
  const double loss = losses.loss(batch.policy, all_rows(40), focops_loss(a, 1.5, eta), &gradient);
  EXPECT_NEAR(loss, hand_focops_loss(batch, anchor, a, 1.5, eta), 1e-12);
  const Eigen::VectorXd expected =
      central_difference_gradient(batch, [&] { return hand_focops_loss(batch, anchor, a, 1.5, eta); });
  EXPECT_LT((gradient - expected).norm(), 1e-6 * expected.norm());
  EXPECT_NEAR(losses.mean_kl(batch.policy), kl.mean(), 1e-14);
}

TEST(FirstOrderLosses, CupProjectionLossMatchesTheHandWrittenLossAndFiniteDifferences) {
  SyntheticBatch batch(40, 7, 8);
  const Eigen::MatrixXd anchor = move_policy(batch, 0.05, 13);
  const Eigen::VectorXd a = 1.3 * batch.cost_advantages;  // c nu A^C
  PolicySurrogate surrogate = batch.surrogate();
  SampleLossBatch losses(surrogate, anchor);
  Eigen::VectorXd gradient;
  // A subset of rows: the minibatch mean is over those rows only.
  std::vector<Eigen::Index> rows = {3, 17, 5, 39, 22, 0, 11};
  const double loss = losses.loss(batch.policy, rows, cup_projection_loss(a), &gradient);
  const Eigen::VectorXd rho = batch.ratios();
  const Eigen::VectorXd kl = sample_kls(batch, anchor);
  double expected_loss = 0;
  for (Eigen::Index i : rows) expected_loss += (kl[i] + rho[i] * a[i]) / 7.0;
  EXPECT_NEAR(loss, expected_loss, 1e-12);
  const Eigen::VectorXd expected = central_difference_gradient(batch, [&] {
    const Eigen::VectorXd r = batch.ratios();
    const Eigen::VectorXd k = sample_kls(batch, anchor);
    double sum = 0;
    for (Eigen::Index i : rows) sum += (k[i] + r[i] * a[i]) / 7.0;
    return sum;
  });
  EXPECT_LT((gradient - expected).norm(), 1e-6 * expected.norm());
  (void)hand_cup_loss;  // the whole-batch form is used below
  EXPECT_NEAR(losses.loss(batch.policy, all_rows(40), cup_projection_loss(a), nullptr), hand_cup_loss(batch, anchor, a),
              1e-12);
}

// ---------------------------------------------------------------------------
// Whole updates on a tiny batch: a linear policy mu = w s + b (1 -> 1, no
// hidden layer), sigma = 0.5, two samples, one minibatch per pass. The
// expected steps below are Adam's (beta 0.9 / 0.999, eps 1e-8) on gradients
// written out by hand.

struct TinyBatch {
  Rng rng{1};
  GaussianPolicy policy{1, 1, {}, rng};
  Eigen::MatrixXd observations{{0.5}, {-1.0}};
  Eigen::MatrixXd actions{{0.3}, {-0.2}};
  Eigen::VectorXd advantages{{1.0, -2.0}};
  Eigen::MatrixXd cost_advantages{{0.5}, {1.5}};
  Eigen::VectorXd old_log_probs = Eigen::VectorXd(2);
  double w0 = 0.2, b0 = -0.1;
  static constexpr double kSigma = 0.5;

  TinyBatch() {
    policy.set_std(kSigma);
    policy.mean_net().set_parameters(Eigen::Vector2d(w0, b0));
    for (int i = 0; i < 2; ++i) old_log_probs[i] = log_prob(i, w0, b0);  // the batch's own policy
  }
  double mu(int i, double w, double b) const { return w * observations(i, 0) + b; }
  double log_prob(int i, double w, double b) const {
    const double z = (actions(i, 0) - mu(i, w, b)) / kSigma;
    return -0.5 * z * z - std::log(kSigma) - 0.5 * std::log(2 * std::numbers::pi);
  }
  double ratio(int i, double w, double b) const { return std::exp(log_prob(i, w, b) - old_log_probs[i]); }
  PolicySurrogate surrogate() const {
    return PolicySurrogate(observations, actions, old_log_probs, advantages, cost_advantages);
  }
};

RunConfig tiny_config(Algorithm alg) {
  RunConfig config = testing::config_for(alg);
  config.first_order.actor_lr = 0.01;
  config.first_order.update_iters = 2;
  config.first_order.policy_minibatch_size = 64;  // one minibatch of both samples
  config.first_order.kl_early_stop = false;
  config.first_order.max_grad_norm = 0.0;
  config.first_order.clip = 0.2;
  config.multiplier.lambda_optimizer = LambdaOptimizer::sgd;
  config.multiplier.lambda_lr = 0.05;
  config.multiplier.lagrangian_multiplier_init = 0.001;
  return config;
}

// d/d(w, b) of 1/2 sum_i coef_i rho_i with d rho_i / d mu_i = rho_i (a_i - mu_i) / sigma^2.
void add_ratio_gradient(const TinyBatch& t, double w, double b, const double coef[2], double& gw, double& gb) {
  for (int i = 0; i < 2; ++i) {
    const double d_mu = coef[i] * t.ratio(i, w, b) * (t.actions(i, 0) - t.mu(i, w, b)) / (TinyBatch::kSigma * TinyBatch::kSigma) / 2;
    gw += d_mu * t.observations(i, 0);
    gb += d_mu;
  }
}

// The parameters after `passes` hand-computed PPO passes of one minibatch on
// advantages a_hat from (w0, b0), and how many sample-passes the clip held.
struct HandPpo {
  double w = 0, b = 0;
  int held_count = 0;
};
HandPpo hand_ppo_passes(const TinyBatch& tiny, const double a_hat[2], double clip, double lr, int passes) {
  HandAdam adam_w, adam_b;
  HandPpo result{tiny.w0, tiny.b0, 0};
  for (int pass = 0; pass < passes; ++pass) {
    double coef[2];
    for (int i = 0; i < 2; ++i) {
      const double rho = tiny.ratio(i, result.w, result.b);
      const bool held = (a_hat[i] > 0 && rho > 1 + clip) || (a_hat[i] < 0 && rho < 1 - clip);
      result.held_count += held;
      coef[i] = held ? 0.0 : -a_hat[i];  // d l_i / d rho_i of -min(rho A, clip(rho) A)
    }
    double gw = 0, gb = 0;
    add_ratio_gradient(tiny, result.w, result.b, coef, gw, gb);
    result.w += adam_w.step(gw, lr);
    result.b += adam_b.step(gb, lr);
  }
  return result;
}

TEST(FirstOrderUpdates, PpoLagTakesTheHandComputedAdamSteps) {
  TinyBatch tiny;
  PolicySurrogate surrogate = tiny.surrogate();
  Ppo ppo_lag(tiny_config(Algorithm::ppo_lag));
  Rng shuffle(3);
  PolicyUpdateInputs inputs{tiny.policy, surrogate, 35.0, 100.0, testing::single_process(), {}, &shuffle};
  ppo_lag.update(inputs);
  // lambda = 0.001 + 0.05 (35 - 25) = 0.501; A_hat = (A - lambda A^C) / (1 + lambda).
  const double lambda = 0.501;
  const double a_hat[2] = {(1.0 - lambda * 0.5) / (1 + lambda), (-2.0 - lambda * 1.5) / (1 + lambda)};
  const HandPpo expected = hand_ppo_passes(tiny, a_hat, 0.2, 0.01, 2);
  EXPECT_NEAR(tiny.policy.mean_net().parameters()[0], expected.w, 1e-12);
  EXPECT_NEAR(tiny.policy.mean_net().parameters()[1], expected.b, 1e-12);
  EXPECT_NEAR(ppo_lag.multipliers()->value(0), lambda, 1e-15);
  // Adam's first steps move every parameter by about lr.
  EXPECT_GT(std::abs(expected.w - tiny.w0), 0.01);
}

TEST(FirstOrderUpdates, PpoClipsASampleOnceItsRatioLeavesTheRange) {
  // Adam's first step (lr 0.2 on w and b) moves sample 0's mean onto its
  // action: rho_0 = exp(0.5 * 0.3^2 / 0.25) = 1.197 > 1 + clip with A_0 > 0,
  // so the second pass must ignore it (hand oracle as above).
  TinyBatch tiny;
  PolicySurrogate surrogate = tiny.surrogate();
  RunConfig config = tiny_config(Algorithm::ppo);
  config.first_order.actor_lr = 0.2;
  config.first_order.clip = 0.1;
  Ppo ppo(config);
  Rng shuffle(3);
  ppo.update(PolicyUpdateInputs{tiny.policy, surrogate, 0.0, 100.0, testing::single_process(), {}, &shuffle});
  const double a[2] = {tiny.advantages[0], tiny.advantages[1]};
  const HandPpo expected = hand_ppo_passes(tiny, a, 0.1, 0.2, 2);
  EXPECT_EQ(expected.held_count, 1);  // the clip held sample 0 in the second pass
  EXPECT_NEAR(tiny.policy.mean_net().parameters()[0], expected.w, 1e-12);
  EXPECT_NEAR(tiny.policy.mean_net().parameters()[1], expected.b, 1e-12);
}

TEST(FirstOrderUpdates, FocopsTakesTheHandComputedAdamSteps) {
  TinyBatch tiny;
  PolicySurrogate surrogate = tiny.surrogate();
  RunConfig config = tiny_config(Algorithm::focops);
  config.first_order.focops_lam = 1.5;
  config.first_order.focops_eta = 0.02;
  Focops focops(config);
  Rng shuffle(3);
  focops.update(PolicyUpdateInputs{tiny.policy, surrogate, 35.0, 100.0, testing::single_process(), {}, &shuffle});
  const double nu = 0.501;
  const double a_hat[2] = {1.0 - nu * 0.5, -2.0 - nu * 1.5};  // A - nu A^C (no normalisation)
  HandAdam adam_w, adam_b;
  double w = tiny.w0, b = tiny.b0;
  for (int pass = 0; pass < 2; ++pass) {
    double coef[2];
    double gw = 0, gb = 0;
    for (int i = 0; i < 2; ++i) {
      const double diff = tiny.mu(i, w, b) - tiny.mu(i, tiny.w0, tiny.b0);
      const double kl = diff * diff / (2 * TinyBatch::kSigma * TinyBatch::kSigma);
      const bool in = kl <= 0.02;
      coef[i] = in ? -a_hat[i] / 1.5 : 0.0;
      if (in) {  // d KL_i / d mu_i = (mu_i - mu_old,i) / sigma^2, over N = 2
        gw += diff / (TinyBatch::kSigma * TinyBatch::kSigma) / 2 * tiny.observations(i, 0);
        gb += diff / (TinyBatch::kSigma * TinyBatch::kSigma) / 2;
      }
    }
    add_ratio_gradient(tiny, w, b, coef, gw, gb);
    w += adam_w.step(gw, 0.01);
    b += adam_b.step(gb, 0.01);
  }
  EXPECT_NEAR(tiny.policy.mean_net().parameters()[0], w, 1e-12);
  EXPECT_NEAR(tiny.policy.mean_net().parameters()[1], b, 1e-12);
  EXPECT_NEAR(focops.multipliers()->value(0), nu, 1e-15);
}

TEST(FirstOrderUpdates, FocopsProjectsNuOntoItsUpperBound) {
  // nu = min(max(0, 0.001 + 0.05 (125 - 25)), 2) = 2 (unbounded it would be 5.001), then
  // min(2 + 0.05 * 10, 2) = 2 again; with J_C = 5 it falls to 2 - 0.05 * 20 = 1.
  TinyBatch tiny;
  RunConfig config = tiny_config(Algorithm::focops);
  config.multiplier.lagrangian_upper_bound = 2.0;
  Focops focops(config);
  Rng shuffle(3);
  const double expected[] = {2.0, 2.0, 1.0};
  const double costs[] = {125.0, 35.0, 5.0};
  for (int k = 0; k < 3; ++k) {
    PolicySurrogate surrogate = tiny.surrogate();
    focops.update(PolicyUpdateInputs{tiny.policy, surrogate, costs[k], 100.0, testing::single_process(), {}, &shuffle});
    EXPECT_NEAR(focops.multipliers()->value(0), expected[k], 1e-15) << k;
  }
}

TEST(FirstOrderUpdates, CupTakesThePerformanceThenTheProjectionStepsByHand) {
  TinyBatch tiny;
  PolicySurrogate surrogate = tiny.surrogate();
  RunConfig config = tiny_config(Algorithm::cup);
  config.first_order.update_iters = 1;
  config.gamma = 0.99;
  config.lam_c = 0.95;
  Cup cup(config);
  Rng shuffle(3);
  cup.update(PolicyUpdateInputs{tiny.policy, surrogate, 35.0, 100.0, testing::single_process(), {}, &shuffle});
  const double nu = 0.501;
  const double c = (1 - 0.99 * 0.95) / (1 - 0.99);  // 5.95
  HandAdam adam_w, adam_b;
  // Step 1: PPO on A at theta_old (rho = 1: nothing clipped).
  double w = tiny.w0, b = tiny.b0;
  {
    const double coef[2] = {-1.0, 2.0};
    double gw = 0, gb = 0;
    add_ratio_gradient(tiny, w, b, coef, gw, gb);
    w += adam_w.step(gw, 0.01);
    b += adam_b.step(gb, 0.01);
  }
  // Step 2 at pi_{k+1/2}: KL to itself is 0 with zero gradient; the loss's
  // gradient is that of 1/2 sum_i c nu A^C_i rho_i (rho to the batch's policy).
  {
    const double coef[2] = {c * nu * 0.5, c * nu * 1.5};
    double gw = 0, gb = 0;
    add_ratio_gradient(tiny, w, b, coef, gw, gb);
    w += adam_w.step(gw, 0.01);
    b += adam_b.step(gb, 0.01);
  }
  EXPECT_NEAR(tiny.policy.mean_net().parameters()[0], w, 1e-12);
  EXPECT_NEAR(tiny.policy.mean_net().parameters()[1], b, 1e-12);
}

TEST(FirstOrderUpdates, TheKlEarlyStopEndsThePassesOnceTheKlExceedsTheTarget) {
  TinyBatch tiny;
  PolicySurrogate surrogate = tiny.surrogate();
  RunConfig config = tiny_config(Algorithm::ppo);
  config.first_order.update_iters = 50;
  config.first_order.kl_early_stop = true;
  config.trust_region.target_kl = 1e-3;
  Ppo ppo(config);
  Rng shuffle(3);
  const PolicyUpdateResult result =
      ppo.update(PolicyUpdateInputs{tiny.policy, surrogate, 0.0, 100.0, testing::single_process(), {}, &shuffle});
  const int passes = static_cast<int>(result.value("Misc/StopIter"));
  EXPECT_LT(passes, 50);
  // Hand check: the KL (summed over the one action dimension) after the last pass exceeds the target.
  const double w = tiny.policy.mean_net().parameters()[0], b = tiny.policy.mean_net().parameters()[1];
  double kl = 0;
  for (int i = 0; i < 2; ++i) {
    const double diff = tiny.mu(i, w, b) - tiny.mu(i, tiny.w0, tiny.b0);
    kl += diff * diff / (2 * TinyBatch::kSigma * TinyBatch::kSigma) / 2;
  }
  EXPECT_GT(kl, 1e-3);
}

TEST(FirstOrderUpdates, TheGradientIsRescaledToMaxGradNorm) {
  // With max_grad_norm tiny, Adam still moves by lr per parameter on its
  // first step (it is scale-free), so compare against plain arithmetic: the
  // first step is lr g / (|g| + eps) for the rescaled g, i.e. lr sign(g)
  // up to eps / |g|, which is no longer negligible once |g| ~ 1e-8.
  TinyBatch tiny;
  PolicySurrogate surrogate = tiny.surrogate();
  RunConfig config = tiny_config(Algorithm::ppo);
  config.first_order.update_iters = 1;
  config.first_order.max_grad_norm = 1e-8;
  Ppo ppo(config);
  Rng shuffle(3);
  const PolicyUpdateResult result =
      ppo.update(PolicyUpdateInputs{tiny.policy, surrogate, 0.0, 100.0, testing::single_process(), {}, &shuffle});
  const double coef[2] = {-1.0, 2.0};
  double gw = 0, gb = 0;
  add_ratio_gradient(tiny, tiny.w0, tiny.b0, coef, gw, gb);
  const double norm = std::hypot(gw, gb);
  EXPECT_NEAR(result.value("Misc/gradient_norm"), norm, 1e-12);
  const double sw = gw * 1e-8 / norm, sb = gb * 1e-8 / norm;
  EXPECT_NEAR(tiny.policy.mean_net().parameters()[0], tiny.w0 - 0.01 * sw / (std::abs(sw) + 1e-8), 1e-14);
  EXPECT_NEAR(tiny.policy.mean_net().parameters()[1], tiny.b0 - 0.01 * sb / (std::abs(sb) + 1e-8), 1e-14);
}

TEST(FirstOrderUpdates, AnUpdateWithoutAMinibatchRngIsRefused) {
  TinyBatch tiny;
  PolicySurrogate surrogate = tiny.surrogate();
  Ppo ppo(tiny_config(Algorithm::ppo));
  EXPECT_THROW(ppo.update(PolicyUpdateInputs{tiny.policy, surrogate, 0.0, 100.0, testing::single_process()}),
               std::invalid_argument);
}

TEST(PolicyAdam, StateRoundTripsAndRestoredStepsMatch) {
  TinyBatch a, b;
  PolicyAdam first(0.01), second(0.01);
  EXPECT_EQ(first.state().size(), 1u);  // only t = 0 before the first step
  first.step(a.policy.mean_net(), Eigen::Vector2d(0.3, -0.7));
  second.restore_state(first.state());
  EXPECT_EQ(second.state(), first.state());
  ASSERT_EQ(first.state().size(), 5u);
  EXPECT_EQ(first.state()[1].name, "policy_adam/m/0");
  b.policy.mean_net().set_parameters(a.policy.mean_net().parameters());
  first.step(a.policy.mean_net(), Eigen::Vector2d(-0.1, 0.2));
  second.step(b.policy.mean_net(), Eigen::Vector2d(-0.1, 0.2));
  EXPECT_EQ(a.policy.mean_net().parameters(), b.policy.mean_net().parameters());
  std::vector<NamedScalar> bad = first.state();
  bad[2].name = "policy_adam/m/7";
  EXPECT_THROW(second.restore_state(bad), std::invalid_argument);
  bad = first.state();
  bad.pop_back();
  EXPECT_THROW(second.restore_state(bad), std::invalid_argument);
}

}  // namespace
}  // namespace bsg::algos
