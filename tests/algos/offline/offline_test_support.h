// Helpers of the offline learners' tests (cpq_test.cpp, bcq_lag_test.cpp, coptidice_test.cpp): a
// batch, one critic's value at one row, and central differences over a network's parameters.
#pragma once

#include <gtest/gtest.h>

#include <Eigen/Core>

#include "algos/offline/offline_algorithm.h"
#include "common/mlp.h"
#include "common/random.h"
#include "../../common/random_matrices.h"

namespace bsg::testing {

// Four rows: observations uniform in [-1.5, 1.5], actions in [-0.9, 0.9], fixed rewards and costs,
// the third row terminal.
inline algos::OfflineBatch random_offline_batch(Rng& rng, int observation_size, int action_size) {
  algos::OfflineBatch b;
  b.observations.resize(4, observation_size);
  b.next_observations.resize(4, observation_size);
  b.actions.resize(4, action_size);
  for (Eigen::Index k = 0; k < b.observations.size(); ++k) b.observations.data()[k] = uniform(rng, -1.5, 1.5);
  for (Eigen::Index k = 0; k < b.next_observations.size(); ++k) b.next_observations.data()[k] = uniform(rng, -1.5, 1.5);
  for (Eigen::Index k = 0; k < b.actions.size(); ++k) b.actions.data()[k] = uniform(rng, -0.9, 0.9);
  b.rewards = Eigen::Vector4d(1.0, -2.0, 0.5, 3.0);
  b.costs = Eigen::Vector4d(0.0, 1.0, 1.0, 0.0);
  b.terminals = Eigen::Vector4d(0.0, 0.0, 1.0, 0.0);
  return b;
}

// The standardisation that leaves observations as they are.
inline algos::ObservationScaling unit_scaling(int observation_size) {
  return {Eigen::VectorXd::Zero(observation_size), Eigen::VectorXd::Ones(observation_size)};
}

// The small float64 networks of the VAE-based learners' tests (BCQ-Lag, CPQ): tanh, smooth for
// the central differences; 3 sampled actions, 20-step episodes, gamma 0.9, scaled reward and cost.
template <typename Options>
void set_small_vae_learner_options(Options& options, double cost_limit) {
  options.hidden_sizes = {6};
  options.mlp = MlpOptions{};
  options.vae_hidden_size = 5;
  options.sampled_actions = 3;
  options.cost_limit = cost_limit;
  options.episode_length = 20;
  options.gamma = 0.9;
  options.reward_scale = 0.1;
  options.cost_scale = 2.0;
}

// Q([s, a]) from the critic's single-sample pass.
inline double q_of(const Mlp& critic, const Eigen::VectorXd& s, const Eigen::VectorXd& a) {
  Eigen::VectorXd input(s.size() + a.size());
  input << s, a;
  return critic.forward(input)[0];
}

// Central differences of `loss` over every parameter of `network` against `analytic`.
template <typename Loss>
void expect_central_differences(Mlp& network, const Eigen::VectorXd& analytic, Loss loss, double tolerance = 1e-6) {
  const Eigen::VectorXd theta = network.parameters();
  const double h = 1e-6;
  for (Eigen::Index k = 0; k < theta.size(); ++k) {
    Eigen::VectorXd shifted = theta;
    shifted[k] += h;
    network.set_parameters(shifted);
    const double up = loss();
    shifted[k] -= 2 * h;
    network.set_parameters(shifted);
    const double down = loss();
    network.set_parameters(theta);
    EXPECT_NEAR(analytic[k], (up - down) / (2 * h), tolerance) << k;
  }
}

}  // namespace bsg::testing
