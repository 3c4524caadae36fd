// Test helpers for the five algorithms' updates: a synthetic batch on a random
// small policy, hand-written surrogates and KL (independent of the core's
// PolicySurrogate), dense linear operators for the 2-D oracles.
#pragma once

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <numeric>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "algos/core/algorithm.h"
#include "algos/trust_region/conjugate_gradient.h"
#include "algos/core/gaussian_policy.h"
#include "algos/core/policy_surrogate.h"
#include "common/random.h"
#include "common/run_config.h"

namespace bsg::testing {

// A random 3 -> 2 policy (hidden 8-8, sigma 0.4) built from `policy_seed`, and
// N samples drawn from it with `batch_seed`: normalised observations, actions,
// their log-probabilities, N(0,1) reward advantages and cost advantages with a
// positive mean (a cost that grows along some directions).
struct SyntheticBatch {
  static constexpr int kObservationSize = 3;
  static constexpr int kActionSize = 2;

  Rng policy_rng;
  algos::GaussianPolicy policy;
  Eigen::MatrixXd observations, actions;
  Eigen::VectorXd old_log_probs, advantages, cost_advantages;

  SyntheticBatch(Eigen::Index n, std::uint64_t policy_seed, std::uint64_t batch_seed)
      : policy_rng(policy_seed),
        policy(kObservationSize, kActionSize, {8, 8}, policy_rng),
        observations(n, kObservationSize),
        actions(n, kActionSize),
        old_log_probs(n),
        advantages(n),
        cost_advantages(n) {
    policy.set_std(0.4);
    Rng rng(batch_seed);
    MlpSampleWorkspace workspace;
    Eigen::VectorXd action(kActionSize);
    for (Eigen::Index i = 0; i < n; ++i) {
      for (int j = 0; j < kObservationSize; ++j) observations(i, j) = standard_normal(rng);
      old_log_probs[i] = policy.sample_action(observations.row(i).transpose(), action, rng, workspace);
      actions.row(i) = action.transpose();
      advantages[i] = standard_normal(rng);
      cost_advantages[i] = 0.5 + standard_normal(rng);
    }
  }

  algos::PolicySurrogate surrogate() const {
    return algos::PolicySurrogate(observations, actions, old_log_probs, advantages, cost_advantages);
  }

  Eigen::MatrixXd means() const {
    Eigen::MatrixXd result(observations.rows(), kActionSize);
    for (Eigen::Index i = 0; i < observations.rows(); ++i) {
      result.row(i) = policy.mean_net().forward(observations.row(i).transpose()).transpose();
    }
    return result;
  }

  // Hand-written ratios rho_i = exp(log pi(a_i|s_i) - log pi_old,i) at the current parameters.
  Eigen::VectorXd ratios() const {
    const Eigen::MatrixXd mu = means();
    const double sigma = policy.std();
    Eigen::VectorXd rho(observations.rows());
    for (Eigen::Index i = 0; i < observations.rows(); ++i) {
      const double log_prob = -0.5 * (actions.row(i) - mu.row(i)).squaredNorm() / (sigma * sigma) -
                              kActionSize * std::log(sigma) - 0.5 * kActionSize * std::log(2.0 * std::numbers::pi);
      rho[i] = std::exp(log_prob - old_log_probs[i]);
    }
    return rho;
  }
  double reward_surrogate() const { return ratios().dot(advantages) / static_cast<double>(advantages.size()); }
  double cost_surrogate() const { return ratios().dot(cost_advantages) / static_cast<double>(advantages.size()); }

  // Mean KL over samples and action dims (docs/algorithms.md#mean-kl) between `old_means` and the current means.
  double kl_from(const Eigen::MatrixXd& old_means) const {
    const double sigma = policy.std();
    return (old_means - means()).squaredNorm() / (2.0 * sigma * sigma) /
           static_cast<double>(old_means.rows() * old_means.cols());
  }
};

// Central differences of `loss` (a function of the policy's mean-net parameters) at the current
// parameters, which it leaves as they were.
template <class Loss>
Eigen::VectorXd central_difference_gradient(SyntheticBatch& batch, const Loss& loss) {
  const Eigen::VectorXd theta = batch.policy.mean_net().parameters();
  Eigen::VectorXd gradient(theta.size());
  const double h = 1e-6;
  for (Eigen::Index k = 0; k < theta.size(); ++k) {
    Eigen::VectorXd shifted = theta;
    shifted[k] += h;
    batch.policy.mean_net().set_parameters(shifted);
    const double up = loss();
    shifted[k] = theta[k] - h;
    batch.policy.mean_net().set_parameters(shifted);
    const double down = loss();
    gradient[k] = (up - down) / (2 * h);
  }
  batch.policy.mean_net().set_parameters(theta);
  return gradient;
}

// The batch's surrogates and policy means before a constrained update (CPO,
// PCPO), and the end-to-end constrained tests an accepted update must pass
// (docs/algorithms.md#test-oracles): the KL stays within 1.5 target_kl, the cost surrogate rises
// by at most max(-c, 0), and while feasible (c < 0) the reward surrogate does
// not fall. c is the normalised constraint value the update was given.
struct BeforeConstrainedUpdate {
  explicit BeforeConstrainedUpdate(const SyntheticBatch& batch)
      : reward_surrogate(batch.reward_surrogate()),
        cost_surrogate(batch.cost_surrogate()),
        means(batch.means()) {}

  double reward_surrogate;
  double cost_surrogate;
  Eigen::MatrixXd means;
};

inline void expect_passes_constrained_tests(const SyntheticBatch& batch,
                                            const BeforeConstrainedUpdate& before, double c,
                                            double target_kl) {
  EXPECT_LE(batch.kl_from(before.means), 1.5 * target_kl);
  EXPECT_LE(batch.cost_surrogate() - before.cost_surrogate, std::max(-c, 0.0) + 1e-15);
  if (c < 0.0) {
    EXPECT_GE(batch.reward_surrogate(), before.reward_surrogate);
  }
}

// Adam's update of one parameter after steps with gradients g[0..t-1].
struct HandAdam {
  double m = 0, v = 0;
  int t = 0;
  double step(double g, double lr) {
    ++t;
    m = 0.9 * m + 0.1 * g;
    v = 0.999 * v + 0.001 * g * g;
    const double m_hat = m / (1 - std::pow(0.9, t));
    const double v_hat = v / (1 - std::pow(0.999, t));
    return -lr * m_hat / (std::sqrt(v_hat) + 1e-8);
  }
};

// The row indices 0 .. n-1 (a minibatch of the whole batch).
inline std::vector<Eigen::Index> all_rows(Eigen::Index n) {
  std::vector<Eigen::Index> rows(static_cast<std::size_t>(n));
  std::iota(rows.begin(), rows.end(), Eigen::Index{0});
  return rows;
}

inline const MpiContext& single_process() {
  static const MpiContext context = MpiContext::single_process();
  return context;
}

inline algos::PolicyUpdateInputs inputs_for(SyntheticBatch& batch, algos::PolicySurrogate& surrogate, double mean_episode_cost,
                                     double mean_episode_length, const MpiContext& mpi = single_process()) {
  return algos::PolicyUpdateInputs{batch.policy, surrogate, mean_episode_cost, mean_episode_length, mpi};
}

// Every on-policy algorithm of the table (common/algorithms.h) in its order, so that tests
// looping over the algorithms cover a new row without an edit.
inline std::vector<Algorithm> on_policy_algorithms() {
  std::vector<Algorithm> algorithms;
  for (const AlgorithmInfo& info : kAlgorithms) {
    if (info.family == AlgorithmFamily::trust_region || info.family == AlgorithmFamily::first_order) {
      algorithms.push_back(info.alg);
    }
  }
  return algorithms;
}

// A RunConfig for `alg` with the algorithm's shipped defaults that matter here.
inline RunConfig config_for(Algorithm alg) {
  RunConfig config;
  config.alg = alg;
  config.trust_region.target_kl = 0.01;
  config.cost_limit = 25.0;
  config.use_cost_value_function = !ignores_cost(alg);
  switch (alg) {
    case Algorithm::trpo: break;
    case Algorithm::lag_trpo:
      config.multiplier.lambda_optimizer = LambdaOptimizer::sgd;
      config.multiplier.lambda_lr = 0.05;
      break;
    case Algorithm::cpo: config.trust_region.backtrack_budget = 20; break;
    case Algorithm::pdo:
      config.multiplier.lambda_optimizer = LambdaOptimizer::adam;
      config.multiplier.lambda_lr = 0.001;
      break;
    case Algorithm::pcpo: config.trust_region.backtrack_budget = 25; break;
    case Algorithm::ppo:
    case Algorithm::ppo_lag:
    case Algorithm::focops:
    case Algorithm::cup:
    case Algorithm::p3o:
    case Algorithm::ipo:
    case Algorithm::ppo_saute:
    case Algorithm::ppo_early_terminated:
    case Algorithm::ppo_simmer:  // the first-order defaults of configs/algorithms (OmniSafe's)
      config.trust_region.target_kl = 0.02;
      config.multiplier.lambda_optimizer = LambdaOptimizer::adam;
      config.multiplier.lambda_lr = 0.035;
      break;
    case Algorithm::rcpo:  // OmniSafe's RCPO.yaml
      config.multiplier.lambda_optimizer = LambdaOptimizer::adam;
      config.multiplier.lambda_lr = 0.035;
      break;
    default: break;  // the RunConfig defaults (TRPO's, crpo_tolerance 2); off-policy: no on-policy update
  }
  return config;
}

// The dense matrix M as a LinearOperator.
inline algos::LinearOperator dense_operator(const Eigen::MatrixXd& matrix) {
  return [matrix](const Eigen::Ref<const Eigen::VectorXd>& direction, Eigen::Ref<Eigen::VectorXd> product) {
    product = matrix * direction;
  };
}

// A random symmetric positive definite n x n matrix with eigenvalues of order 1.
inline Eigen::MatrixXd random_spd(int n, Rng& rng) {
  Eigen::MatrixXd u(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) u(i, j) = uniform(rng, -1.0, 1.0);
  return u * u.transpose() / n + 0.5 * Eigen::MatrixXd::Identity(n, n);
}

inline Eigen::VectorXd random_vector(int n, Rng& rng) {
  Eigen::VectorXd v(n);
  for (int i = 0; i < n; ++i) v[i] = standard_normal(rng);
  return v;
}

inline Eigen::VectorXd vec2(double a, double b) {
  Eigen::VectorXd v(2);
  v << a, b;
  return v;
}

// True if both vectors hold exactly the same bits.
inline bool bit_identical(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  if (a.size() != b.size()) return false;
  for (Eigen::Index i = 0; i < a.size(); ++i) {
    if (std::memcmp(&a[i], &b[i], sizeof(double)) != 0) return false;
  }
  return true;
}

// A PID multiplier and an SGD multiplier that reach the same lambda drive the
// same policy step; the PID terms are logged beside it (three more columns).
// J_C = 30, d = 25: P = 0.1 * 5 = 0.5, I = 0.001 + 0.05 * 5 = 0.251,
// D = 0.2 * max(0, 30 - 0) = 6, lambda = 6.751: the step an SGD multiplier
// reaching the same lambda (6.501 + 0.05 * 5) takes.
template <class Update>
void expect_pid_multiplier_steers_like_sgd(Algorithm algorithm) {
  RunConfig pid_config = testing::config_for(algorithm);
  pid_config.multiplier.lambda_optimizer = LambdaOptimizer::pid;
  pid_config.multiplier.lagrangian_multiplier_init = 0.001;
  pid_config.multiplier.pid_kp = 0.1;
  pid_config.multiplier.pid_ki = 0.05;
  pid_config.multiplier.pid_kd = 0.2;
  RunConfig sgd_config = testing::config_for(algorithm);
  sgd_config.multiplier.lambda_optimizer = LambdaOptimizer::sgd;
  sgd_config.multiplier.lagrangian_multiplier_init = 6.501;
  sgd_config.multiplier.lambda_lr = 0.05;

  SyntheticBatch pid_batch(64, 3, 4);
  SyntheticBatch sgd_batch(64, 3, 4);
  algos::PolicySurrogate pid_surrogate = pid_batch.surrogate();
  algos::PolicySurrogate sgd_surrogate = sgd_batch.surrogate();
  Update pid(pid_config);
  Update sgd(sgd_config);
  const algos::PolicyUpdateResult pid_result = pid.update(testing::inputs_for(pid_batch, pid_surrogate, 30.0, 100.0));
  const algos::PolicyUpdateResult sgd_result = sgd.update(testing::inputs_for(sgd_batch, sgd_surrogate, 30.0, 100.0));

  EXPECT_NEAR(pid_result.value("PID/P"), 0.5, 1e-15);
  EXPECT_NEAR(pid_result.value("PID/I"), 0.251, 1e-15);
  EXPECT_NEAR(pid_result.value("PID/D"), 6.0, 1e-15);
  EXPECT_NEAR(pid_result.value("LagrangeMultiplier"), 6.751, 1e-14);
  EXPECT_NEAR(sgd_result.value("LagrangeMultiplier"), 6.751, 1e-14);
  EXPECT_THROW(sgd_result.value("PID/P"), std::out_of_range);
  ASSERT_GE(pid_result.value("Misc/AcceptanceStep"), 1.0);
  EXPECT_EQ(pid_result.value("Misc/AcceptanceStep"), sgd_result.value("Misc/AcceptanceStep"));
  EXPECT_TRUE(pid_batch.policy.mean_net().parameters().isApprox(sgd_batch.policy.mean_net().parameters(), 1e-10));
  const std::vector<std::string> names = pid.diagnostic_names();
  ASSERT_EQ(names.size(), pid_result.diagnostics.size());
  for (std::size_t i = 0; i < names.size(); ++i) EXPECT_EQ(pid_result.diagnostics[i].name, names[i]);
  EXPECT_EQ(names.size(), sgd.diagnostic_names().size() + 3);
}

}  // namespace bsg::testing
