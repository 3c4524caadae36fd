#include "algos/algorithm.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace bsg {

double PolicyUpdateResult::value(std::string_view name) const {
  for (const NamedScalar& entry : diagnostics) {
    if (entry.name == name) return entry.value;
  }
  throw std::out_of_range("PolicyUpdateResult::value: no diagnostic named '" + std::string(name) + "'");
}

std::vector<std::string> common_diagnostic_names() {
  return {"Loss/Pi", "Loss/DeltaPi", "Entropy", "KL", "PolicyRatio"};
}

ConjugateGradientOptions conjugate_gradient_options(const RunConfig& config) {
  ConjugateGradientOptions options;
  options.iterations = config.cg_iters;
  return options;
}

FisherVectorProductOptions fisher_vector_product_options(const RunConfig& config) {
  FisherVectorProductOptions options;
  options.damping_coeff = config.cg_damping;
  options.subsample_stride = config.fvp_subsample;
  return options;
}

LineSearchOptions line_search_options(const RunConfig& config) {
  LineSearchOptions options;
  options.budget = config.backtrack_budget;
  options.decay = config.backtrack_decay;
  options.target_kl = config.target_kl;
  options.kl_accept_factor = config.kl_accept_factor;
  return options;
}

LinearOperator as_linear_operator(FisherVectorProduct& fisher) {
  return [&fisher](const Eigen::Ref<const Eigen::VectorXd>& direction, Eigen::Ref<Eigen::VectorXd> product) {
    fisher.apply(direction, product);
  };
}

PolicyGradients averaged_policy_gradients(const PolicyUpdateInputs& inputs) {
  const Eigen::Index num_parameters = inputs.policy.mean_net().num_parameters();
  Eigen::VectorXd both(2 * num_parameters);
  inputs.surrogate.gradient(inputs.policy, 1.0, 0.0, both.head(num_parameters));  // grad L_R
  inputs.surrogate.gradient(inputs.policy, 0.0, 1.0, both.tail(num_parameters));  // grad L_C
  inputs.mpi.average_in_place(both);                                               // one allreduce
  PolicyGradients gradients;
  gradients.reward = both.head(num_parameters);  // g = avg grad L_R
  gradients.cost = both.tail(num_parameters);    // b = avg grad L_C
  return gradients;
}

void apply_line_search_result(GaussianPolicy& policy, const Eigen::VectorXd& theta_old,
                              const LineSearchResult& result) {
  if (result.accepted()) {
    policy.mean_net().set_parameters(theta_old + result.step);  // theta = theta_old + final step
  } else {
    policy.mean_net().set_parameters(theta_old);  // bit-identical restore
  }
}

double per_step_constraint_violation(double mean_episode_cost, double mean_episode_length, double cost_limit) {
  if (!std::isfinite(mean_episode_cost)) {
    throw std::invalid_argument("per_step_constraint_violation: mean_episode_cost (J_C) is not finite: " +
                                std::to_string(mean_episode_cost) + " (no episode completed this epoch?)");
  }
  if (!std::isfinite(mean_episode_length) || mean_episode_length < 0.0) {
    throw std::invalid_argument("per_step_constraint_violation: mean_episode_length (L) must be finite and >= 0, got " +
                                std::to_string(mean_episode_length));
  }
  return (mean_episode_cost - cost_limit) / (mean_episode_length + 1e-8);  // c = (J_C - d) / (L + 1e-8)
}

void check_mean_episode_cost(const PolicyUpdateInputs& inputs, std::string_view algorithm) {
  if (!std::isfinite(inputs.mean_episode_cost)) {
    throw std::invalid_argument(std::string(algorithm) + ": mean_episode_cost (J_C) is not finite: " +
                                std::to_string(inputs.mean_episode_cost) + " (no episode completed this epoch?)");
  }
}

PolicyUpdateStart begin_policy_update(const PolicyUpdateInputs& inputs) {
  PolicyUpdateStart start;
  start.theta_old = inputs.policy.mean_net().parameters();  // theta_old <- theta
  inputs.surrogate.set_reference_means(inputs.policy);      // mu_old for the KL
  start.before = inputs.surrogate.evaluate(inputs.policy);
  return start;
}

double weighted_surrogate_loss(const SurrogateValues& values, double reward_weight, double cost_weight) {
  return -(reward_weight * values.reward_surrogate + cost_weight * values.cost_surrogate);
}

LossEvaluator surrogate_loss_evaluator(const PolicyUpdateInputs& inputs, const Eigen::VectorXd& theta_old,
                                       double reward_weight, double cost_weight) {
  return [&inputs, &theta_old, reward_weight, cost_weight](const Eigen::Ref<const Eigen::VectorXd>& step) {
    inputs.policy.mean_net().set_parameters(theta_old + step);  // theta_j = theta_old + 0.8^j Delta
    const SurrogateValues values = inputs.surrogate.evaluate(inputs.policy);
    return LossAndKl{weighted_surrogate_loss(values, reward_weight, cost_weight), values.kl};
  };
}

ConstrainedEvaluator constrained_evaluator(const PolicyUpdateInputs& inputs, const Eigen::VectorXd& theta_old) {
  return [&inputs, &theta_old](const Eigen::Ref<const Eigen::VectorXd>& step) {
    inputs.policy.mean_net().set_parameters(theta_old + step);
    const SurrogateValues values = inputs.surrogate.evaluate(inputs.policy);
    return ConstrainedTrial{-values.reward_surrogate, values.cost_surrogate, values.kl};  // l_R, L_C, KL
  };
}

std::vector<NamedScalar> common_diagnostics(const PolicyUpdateInputs& inputs, const SurrogateValues& before,
                                            double reward_weight, double cost_weight) {
  const SurrogateValues after = inputs.surrogate.evaluate(inputs.policy);
  const double loss_before = weighted_surrogate_loss(before, reward_weight, cost_weight);
  const double loss_after = weighted_surrogate_loss(after, reward_weight, cost_weight);
  return {{"Loss/Pi", loss_before},
          {"Loss/DeltaPi", loss_after - loss_before},
          {"Entropy", inputs.policy.entropy_per_dimension()},
          {"KL", after.kl},
          {"PolicyRatio", after.mean_ratio}};
}

void TrustRegionAlgorithm::restore_state(std::span<const NamedScalar> saved) {
  if (!saved.empty()) {
    throw std::invalid_argument(std::string(name()) + ": restore_state expects an empty state, got " +
                                std::to_string(saved.size()) + " values (first '" + saved.front().name + "')");
  }
}

}  // namespace bsg
