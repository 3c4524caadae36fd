// Helpers of the sequential-update tests: linear Gaussian policies whose log-probabilities,
// ratios and KL are written out by hand here, independently of GaussianPolicy.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <numbers>
#include <vector>

#include "algos/core/gaussian_policy.h"
#include "algos/multi_agent/sequential_batch.h"
#include "common/random.h"

namespace bsg::testing {

// mu = W o + b with a fixed sigma; `parameters` in the MLP's layout (W row-major, then b).
inline algos::GaussianPolicy linear_policy(int observation_size, int action_size, const Eigen::VectorXd& parameters,
                                           double sigma) {
  Rng rng(7);
  algos::GaussianPolicy policy(observation_size, action_size, {}, rng);
  policy.mean_net().set_parameters(parameters);
  policy.set_std(sigma);
  return policy;
}

// mu_i of the linear policy with `parameters`, written out.
inline Eigen::MatrixXd linear_means(const Eigen::MatrixXd& observations, int action_size,
                                    const Eigen::VectorXd& parameters) {
  const auto d_o = observations.cols();
  Eigen::MatrixXd means(observations.rows(), action_size);
  for (Eigen::Index i = 0; i < observations.rows(); ++i) {
    for (int k = 0; k < action_size; ++k) {
      double mu = parameters[action_size * d_o + k];  // b_k
      for (Eigen::Index j = 0; j < d_o; ++j) mu += parameters[k * d_o + j] * observations(i, j);  // W_kj o_j
      means(i, k) = mu;
    }
  }
  return means;
}

// log N(a; mu, sigma^2 I), summed over the action dimensions.
inline double gaussian_log_prob(const Eigen::VectorXd& action, const Eigen::VectorXd& mean, double sigma) {
  double log_prob = 0.0;
  for (Eigen::Index k = 0; k < action.size(); ++k) {
    const double z = (action[k] - mean[k]) / sigma;
    log_prob += -0.5 * z * z - std::log(sigma) - 0.5 * std::log(2.0 * std::numbers::pi);
  }
  return log_prob;
}

// pi_new(a_i|o_i) / pi_old(a_i|o_i) of a linear policy moved from theta_old to theta_new.
inline Eigen::VectorXd linear_ratios(const algos::AgentBatch& batch, const Eigen::VectorXd& theta_old,
                                     const Eigen::VectorXd& theta_new, double sigma) {
  const int d_a = static_cast<int>(batch.actions.cols());
  const Eigen::MatrixXd old_means = linear_means(batch.observations, d_a, theta_old);
  const Eigen::MatrixXd new_means = linear_means(batch.observations, d_a, theta_new);
  Eigen::VectorXd ratios(batch.actions.rows());
  for (Eigen::Index i = 0; i < ratios.size(); ++i) {
    // exp(((a - mu_old)^2 - (a - mu_new)^2) / (2 sigma^2)) per dimension, multiplied
    double exponent = 0.0;
    for (int k = 0; k < d_a; ++k) {
      const double old_d = batch.actions(i, k) - old_means(i, k);
      const double new_d = batch.actions(i, k) - new_means(i, k);
      exponent += (old_d * old_d - new_d * new_d) / (2.0 * sigma * sigma);
    }
    ratios[i] = std::exp(exponent);
  }
  return ratios;
}

// A batch of a linear policy: actions mu + sigma eps, old log-probs written out by hand.
inline algos::AgentBatch linear_batch(const Eigen::MatrixXd& observations, int action_size,
                                      const Eigen::VectorXd& theta_old, double sigma, const Eigen::MatrixXd& eps,
                                      const Eigen::VectorXd& advantages, const Eigen::VectorXd& cost_advantages) {
  algos::AgentBatch batch;
  batch.observations = observations;
  const Eigen::MatrixXd means = linear_means(observations, action_size, theta_old);
  batch.actions = means + sigma * eps;
  batch.old_log_probs.resize(observations.rows());
  for (Eigen::Index i = 0; i < observations.rows(); ++i) {
    batch.old_log_probs[i] =
        gaussian_log_prob(batch.actions.row(i).transpose(), means.row(i).transpose(), sigma);
  }
  batch.advantages = advantages;
  batch.cost_advantages = cost_advantages;
  return batch;
}

// Pointers to each policy, as the rounds take them.
inline std::vector<algos::GaussianPolicy*> pointers_to(std::vector<algos::GaussianPolicy>& policies) {
  std::vector<algos::GaussianPolicy*> pointers;
  for (algos::GaussianPolicy& policy : policies) pointers.push_back(&policy);
  return pointers;
}

inline Eigen::VectorXd vector_of(std::initializer_list<double> values) {
  Eigen::VectorXd v(static_cast<Eigen::Index>(values.size()));
  Eigen::Index i = 0;
  for (const double x : values) v[i++] = x;
  return v;
}

}  // namespace bsg::testing
