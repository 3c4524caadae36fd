// The Gaussian policy pi(a|s) = N(mu_theta(s), sigma^2 I) of docs/algorithms.md#gaussian-policy: an MLP
// for the mean and a fixed, non-trainable scalar standard deviation sigma,
// linearly annealed per epoch. theta is the mean net's flat parameter vector;
// sigma is not part of it. With learn_log_std() (first-order algorithms,
// docs/algorithms.md#learned-log-sigma) sigma becomes a state-independent vector
// exp(s), s = log sigma_j one per action dimension, trained beside theta.
//
// Parameters:
//   observation_size, action_size   d_o, d_a
//   hidden_sizes                    {64, 64}
//   init                            MlpOptions (zero_bias_init = false, Q1)
//   std                             0.5 at construction (kInitialStd); epoch 0 of
//                                   the annealing schedule sets 0.509 (Q2)
#pragma once

#include <Eigen/Core>
#include <vector>

#include "common/mlp.h"
#include "common/random.h"

namespace bsg::algos {

class GaussianPolicy {
 public:
  static constexpr double kInitialStd = 0.5;

  GaussianPolicy(int observation_size, int action_size, const std::vector<int>& hidden_sizes, Rng& rng,
                 MlpOptions init = {});

  int observation_size() const { return mean_net_.input_size(); }
  int action_size() const { return mean_net_.output_size(); }
  Mlp& mean_net() { return mean_net_; }
  const Mlp& mean_net() const { return mean_net_; }

  // The scalar sigma; with a learned log sigma, the mean of the sigma_j (OmniSafe's `std`).
  double std() const;
  // log sigma; with a learned log sigma, the mean of the s_j.
  double log_std() const;
  // Throws with a learned log sigma (nothing sets it from outside then).
  void set_std(double std);

  // Switches to the learned per-dimension log sigma, every s_j = log(initial_std).
  void learn_log_std(double initial_std);
  bool has_learned_std() const { return log_stds_.size() > 0; }
  // s (d_a entries) with a learned log sigma, empty otherwise.
  const Eigen::VectorXd& log_stds() const { return log_stds_; }
  // Throws std::invalid_argument unless `log_stds` has d_a finite entries and the policy learns log sigma.
  void set_log_stds(const Eigen::Ref<const Eigen::VectorXd>& log_stds);

  // sigma_k = 0.499 (1 - k/E) + 0.01 for epoch k of E (docs/algorithms.md#exploration-noise, Q2).
  static double annealed_std(int epoch, int epochs);
  // The same schedule ending early: sigma_k = 0.499 (1 - min(k, n)/n) + 0.01
  // for n = anneal_epochs in [1, E], so that sigma reaches 0.01 at epoch n and
  // holds it (exploration_anneal_epochs); n = 0 is n = E, the schedule above.
  static double annealed_std(int epoch, int epochs, int anneal_epochs);
  void set_annealed_std(int epoch, int epochs) { set_std(annealed_std(epoch, epochs)); }

  // Deterministic action mu_theta(s) (evaluation). No allocation once `workspace` is sized.
  void mean_action(const Eigen::Ref<const Eigen::VectorXd>& observation, Eigen::Ref<Eigen::VectorXd> action,
                   MlpSampleWorkspace& workspace) const;
  // a = mu + sigma eps, eps ~ N(0, I) from `rng` (unclipped, docs/algorithms.md#gaussian-policy); returns log pi(a|s).
  double sample_action(const Eigen::Ref<const Eigen::VectorXd>& observation, Eigen::Ref<Eigen::VectorXd> action,
                       Rng& rng, MlpSampleWorkspace& workspace) const;

  // log pi = -1/2 sum_j (a_j - mu_j)^2 / sigma_j^2 - sum_j log sigma_j - d_a/2 log 2 pi
  double log_prob(const Eigen::Ref<const Eigen::VectorXd>& mean, const Eigen::Ref<const Eigen::VectorXd>& action) const;
  // Row-wise log-probabilities of `actions` under `means` (both N x d_a) into `log_probs` (N).
  void log_prob_batch(const Eigen::Ref<const Eigen::MatrixXd>& means, const Eigen::Ref<const Eigen::MatrixXd>& actions,
                      Eigen::Ref<Eigen::VectorXd> log_probs) const;

  // Entropy of one action dimension: 1/2 + 1/2 log 2 pi + log sigma.
  double entropy_per_dimension() const;

  // Mean KL(old || new) over samples AND action dimensions (docs/algorithms.md#mean-kl, Q8):
  // 1/(N d_a) sum_ij (mu_old,ij - mu_new,ij)^2 / (2 sigma^2), with this policy's sigma.
  double mean_kl(const Eigen::Ref<const Eigen::MatrixXd>& old_means,
                 const Eigen::Ref<const Eigen::MatrixXd>& new_means) const;
  // With a learned log sigma, the same mean of KL(old || new) when the old policy's
  // log sigma was old_log_stds: 1/(N d_a) sum_ij s_j - s_old,j + (sigma_old,j^2 + (mu_old,ij - mu_ij)^2) / (2 sigma_j^2) - 1/2.
  double mean_kl(const Eigen::Ref<const Eigen::MatrixXd>& old_means, const Eigen::Ref<const Eigen::MatrixXd>& new_means,
                 const Eigen::VectorXd& old_log_stds) const;

 private:
  Mlp mean_net_;
  double std_ = kInitialStd;
  Eigen::VectorXd log_stds_;  // s_j = log sigma_j when learned; empty: the scalar std_
};

}  // namespace bsg::algos
