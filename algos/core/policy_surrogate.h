// The surrogate objectives of docs/algorithms.md#surrogates-and-gradients, docs/algorithms.md#mean-kl on one rank's batch and their
// gradients with respect to theta (the policy mean net's parameters):
//   rho_i = exp(log pi_theta(a_i|s_i) - log pi_old,i)
//   L_R   = 1/N sum_i rho_i A_i        (reward surrogate; the loss is l_R = -L_R)
//   L_C   = 1/N sum_i rho_i A^C_i      (cost surrogate)
//   L_Cj  = 1/N sum_i rho_i A^Cj_i     (with m constraints, one per constraint; L_C = L_C1)
//   KL    = mean KL(theta_old || theta) over samples and action dims (Q8)
// Everything here is LOCAL: callers average gradients and line-search values
// over ranks with the MpiContext (g = avg grad L_R, b = avg grad L_C).
//
// The batch is copied once at construction; evaluation and gradients stream
// it through the policy net chunk by chunk (memory O(N d_a) beyond the copy)
// in the net's dtype, reusing preallocated buffers.
#pragma once

#include <Eigen/Core>
#include <array>
#include <span>

#include "algos/core/gaussian_policy.h"
#include "common/constraint_config.h"
#include "common/mlp.h"

namespace bsg::algos {

struct SurrogateValues {
  double reward_surrogate = 0.0;  // L_R
  double cost_surrogate = 0.0;    // L_C (constraint 1's)
  std::array<double, kMaxConstraintCount> cost_surrogates{};  // L_Cj, the first m entries (no allocation)
  double kl = 0.0;                // KL(theta_old || theta) against the reference means
  double mean_ratio = 0.0;        // mean rho (logged as PolicyRatio)
};

class PolicySurrogate {
 public:
  // observations: normalised, N x d_o; actions N x d_a; old_log_probs and
  // advantages length N; cost_advantages N x m, column j holding A^Cj (a vector for m = 1).
  PolicySurrogate(const Eigen::Ref<const Eigen::MatrixXd>& observations,
                  const Eigen::Ref<const Eigen::MatrixXd>& actions,
                  const Eigen::Ref<const Eigen::VectorXd>& old_log_probs,
                  const Eigen::Ref<const Eigen::VectorXd>& advantages,
                  const Eigen::Ref<const Eigen::MatrixXd>& cost_advantages);

  int constraint_count() const { return static_cast<int>(cost_advantages_.cols()); }

  Eigen::Index num_samples() const { return observations_.rows(); }
  const Eigen::MatrixXd& observations() const { return observations_; }
  const Eigen::MatrixXd& actions() const { return actions_; }
  const Eigen::VectorXd& old_log_probs() const { return old_log_probs_; }
  const Eigen::VectorXd& advantages() const { return advantages_; }
  const Eigen::MatrixXd& cost_advantages() const { return cost_advantages_; }  // N x m

  // Stores mu_theta(s_i) at the policy's current parameters as mu_old for the KL.
  void set_reference_means(const GaussianPolicy& policy);
  const Eigen::MatrixXd& reference_means() const { return reference_means_; }

  // L_R, L_C, mean ratio and KL (0 if no reference means were set) at the policy's current parameters.
  SurrogateValues evaluate(const GaussianPolicy& policy);

  // gradient = d/dtheta (reward_weight L_R + cost_weight L_C), local, overwritten.
  // g = gradient(1, 0), b = gradient(0, 1); TRPO-L's -grad l_L = gradient(1/(1+l), -l/(1+l)).
  void gradient(const GaussianPolicy& policy, double reward_weight, double cost_weight,
                Eigen::Ref<Eigen::VectorXd> gradient);
  // gradient = d/dtheta (reward_weight L_R + sum_j cost_weights[j] L_Cj), one weight per constraint.
  void gradient(const GaussianPolicy& policy, double reward_weight, std::span<const double> cost_weights,
                Eigen::Ref<Eigen::VectorXd> gradient);

 private:
  void check_policy(const GaussianPolicy& policy, const char* where) const;
  // Means and ratios at the current parameters into means_ / ratios_.
  void compute_ratios(const GaussianPolicy& policy);
  void check_gradient(const GaussianPolicy& policy, const Eigen::Ref<Eigen::VectorXd>& gradient) const;
  // The streamed gradient of 1/N sum_i rho_i w_i with w_i = sample_weights(first, rows)[i - first].
  template <typename SampleWeights>
  void weighted_gradient(const GaussianPolicy& policy, const SampleWeights& sample_weights,
                         Eigen::Ref<Eigen::VectorXd> gradient);

  Eigen::MatrixXd observations_;
  Eigen::MatrixXd actions_;
  Eigen::VectorXd old_log_probs_;
  Eigen::VectorXd advantages_;
  Eigen::MatrixXd cost_advantages_;  // N x m
  Eigen::VectorXd combined_weights_;  // w_R A + sum_j w_j A^Cj (several constraints)
  Eigen::MatrixXd reference_means_;
  Eigen::VectorXd reference_log_stds_;  // the reference policy's learned log sigma; empty for a fixed sigma
  bool has_reference_means_ = false;
  MlpBatchWorkspace workspace_;
  Eigen::MatrixXd means_;  // mu_theta(s_i) at the last evaluation
  Eigen::VectorXd log_probs_;
  Eigen::VectorXd ratios_;
};

}  // namespace bsg::algos
