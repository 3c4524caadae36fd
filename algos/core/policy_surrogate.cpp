#include "algos/core/policy_surrogate.h"

#include <stdexcept>
#include <string>

namespace bsg::algos {

PolicySurrogate::PolicySurrogate(const Eigen::Ref<const Eigen::MatrixXd>& observations,
                                 const Eigen::Ref<const Eigen::MatrixXd>& actions,
                                 const Eigen::Ref<const Eigen::VectorXd>& old_log_probs,
                                 const Eigen::Ref<const Eigen::VectorXd>& advantages,
                                 const Eigen::Ref<const Eigen::MatrixXd>& cost_advantages)
    : observations_(observations),
      actions_(actions),
      old_log_probs_(old_log_probs),
      advantages_(advantages),
      cost_advantages_(cost_advantages) {
  const Eigen::Index n = observations.rows();
  if (n == 0) throw std::invalid_argument("PolicySurrogate: observations are empty");
  if (actions.rows() != n || old_log_probs.size() != n || advantages.size() != n || cost_advantages.rows() != n) {
    throw std::invalid_argument("PolicySurrogate: observations have " + std::to_string(n) + " rows but actions " +
                                std::to_string(actions.rows()) + ", old_log_probs " +
                                std::to_string(old_log_probs.size()) + ", advantages " +
                                std::to_string(advantages.size()) + ", cost_advantages " +
                                std::to_string(cost_advantages.rows()));
  }
  if (cost_advantages.cols() < 1 || cost_advantages.cols() > kMaxConstraintCount) {
    throw std::invalid_argument("PolicySurrogate: cost_advantages has " + std::to_string(cost_advantages.cols()) +
                                " columns, expected 1.." + std::to_string(kMaxConstraintCount));
  }
  means_.resize(n, actions.cols());
  log_probs_.resize(n);
  ratios_.resize(n);
}

void PolicySurrogate::check_policy(const GaussianPolicy& policy, const char* where) const {
  if (policy.observation_size() != observations_.cols() || policy.action_size() != actions_.cols()) {
    throw std::invalid_argument(std::string(where) + ": the policy maps " + std::to_string(policy.observation_size()) +
                                " -> " + std::to_string(policy.action_size()) + " but the batch holds " +
                                std::to_string(observations_.cols()) + "-d observations and " +
                                std::to_string(actions_.cols()) + "-d actions");
  }
}

void PolicySurrogate::set_reference_means(const GaussianPolicy& policy) {
  check_policy(policy, "PolicySurrogate::set_reference_means");
  reference_means_.resize(num_samples(), policy.action_size());
  policy.mean_net().evaluate_batch(observations_, reference_means_, workspace_);
  reference_log_stds_ = policy.log_stds();
  has_reference_means_ = true;
}

void PolicySurrogate::compute_ratios(const GaussianPolicy& policy) {
  policy.mean_net().evaluate_batch(observations_, means_, workspace_);
  policy.log_prob_batch(means_, actions_, log_probs_);
  ratios_ = (log_probs_ - old_log_probs_).array().exp().matrix();  // rho_i
}

SurrogateValues PolicySurrogate::evaluate(const GaussianPolicy& policy) {
  check_policy(policy, "PolicySurrogate::evaluate");
  compute_ratios(policy);
  const double n = static_cast<double>(num_samples());
  SurrogateValues values;
  values.reward_surrogate = ratios_.dot(advantages_) / n;     // L_R = mean(rho A)
  values.cost_surrogate = ratios_.dot(cost_advantages_.col(0)) / n;  // L_C = mean(rho A^C)
  values.cost_surrogates[0] = values.cost_surrogate;
  for (Eigen::Index j = 1; j < cost_advantages_.cols(); ++j) {
    values.cost_surrogates[static_cast<std::size_t>(j)] = ratios_.dot(cost_advantages_.col(j)) / n;  // L_Cj
  }
  values.mean_ratio = ratios_.mean();
  if (has_reference_means_) {
    values.kl = policy.has_learned_std() ? policy.mean_kl(reference_means_, means_, reference_log_stds_)
                                         : policy.mean_kl(reference_means_, means_);
  }
  return values;
}

void PolicySurrogate::check_gradient(const GaussianPolicy& policy, const Eigen::Ref<Eigen::VectorXd>& gradient) const {
  check_policy(policy, "PolicySurrogate::gradient");
  if (gradient.size() != policy.mean_net().num_parameters()) {
    throw std::invalid_argument("PolicySurrogate::gradient: gradient has " + std::to_string(gradient.size()) +
                                " entries, the policy has " + std::to_string(policy.mean_net().num_parameters()));
  }
}

template <typename SampleWeights>
void PolicySurrogate::weighted_gradient(const GaussianPolicy& policy, const SampleWeights& sample_weights,
                                        Eigen::Ref<Eigen::VectorXd> gradient) {
  const double sigma_squared = policy.std() * policy.std();
  const double n = static_cast<double>(num_samples());
  // One streamed pass: each chunk's means give its ratios and dL/dmu, then its backward pass.
  const auto output_gradient = [&](Eigen::Index first, const Eigen::Ref<const Eigen::MatrixXd>& means,
                                   Eigen::Ref<Eigen::MatrixXd> output_gradients) {
    const Eigen::Index rows = means.rows();
    auto log_probs = log_probs_.segment(first, rows);
    policy.log_prob_batch(means, actions_.middleRows(first, rows), log_probs);
    auto ratios = ratios_.segment(first, rows);
    ratios = (log_probs - old_log_probs_.segment(first, rows)).array().exp().matrix();  // rho_i
    // dL/dmu_ij = 1/N rho_i w_i (a_ij - mu_ij) / sigma^2
    output_gradients = actions_.middleRows(first, rows) - means;
    output_gradients.array().colwise() *= (ratios.array() * sample_weights(first, rows)) / (n * sigma_squared);
  };
  policy.mean_net().gradient_batch(observations_, output_gradient, workspace_, gradient);
}

void PolicySurrogate::gradient(const GaussianPolicy& policy, double reward_weight, double cost_weight,
                               Eigen::Ref<Eigen::VectorXd> gradient) {
  check_gradient(policy, gradient);
  // w_i = w_R A_i + w_C A^C_i
  weighted_gradient(
      policy,
      [&](Eigen::Index first, Eigen::Index rows) {
        return reward_weight * advantages_.segment(first, rows).array() +
               cost_weight * cost_advantages_.col(0).segment(first, rows).array();
      },
      gradient);
}

void PolicySurrogate::gradient(const GaussianPolicy& policy, double reward_weight,
                               std::span<const double> cost_weights, Eigen::Ref<Eigen::VectorXd> gradient) {
  check_gradient(policy, gradient);
  if (static_cast<Eigen::Index>(cost_weights.size()) != cost_advantages_.cols()) {
    throw std::invalid_argument("PolicySurrogate::gradient: " + std::to_string(cost_weights.size()) +
                                " cost weights for " + std::to_string(cost_advantages_.cols()) + " constraints");
  }
  combined_weights_ = reward_weight * advantages_;  // w_i = w_R A_i + sum_j w_j A^Cj_i
  for (Eigen::Index j = 0; j < cost_advantages_.cols(); ++j) {
    combined_weights_ += cost_weights[static_cast<std::size_t>(j)] * cost_advantages_.col(j);
  }
  weighted_gradient(
      policy, [&](Eigen::Index first, Eigen::Index rows) { return combined_weights_.segment(first, rows).array(); },
      gradient);
}

}  // namespace bsg::algos
