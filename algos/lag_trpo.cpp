#include "algos/lag_trpo.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "algos/natural_gradient.h"
#include "algos/trpo.h"

namespace bsg {

SurrogateWeights lagrangian_surrogate_weights(double lagrange_multiplier) {
  if (!std::isfinite(lagrange_multiplier) || lagrange_multiplier < 0.0) {
    throw std::invalid_argument("lagrangian_surrogate_weights: lagrange_multiplier must be finite and >= 0, got " +
                                std::to_string(lagrange_multiplier));
  }
  const double normaliser = 1.0 + lagrange_multiplier;  // 1 + lambda
  return {1.0 / normaliser, -lagrange_multiplier / normaliser};
}

LagTrpo::LagTrpo(const RunConfig& config)
    : TrustRegionAlgorithm(config),
      multiplier_(config) {}

std::vector<std::string> LagTrpo::diagnostic_names() const {
  std::vector<std::string> names = common_diagnostic_names();
  for (std::string& name : trpo_diagnostic_names()) names.push_back(std::move(name));
  for (std::string& name : multiplier_.diagnostic_names()) names.push_back(std::move(name));
  return names;
}

PolicyUpdateResult LagTrpo::update(const PolicyUpdateInputs& inputs) {
  check_mean_episode_cost(inputs, "lag-trpo");
  // 1. lambda update (SGD by default: lambda <- max(0, lambda + alpha_lambda (J_C - d))), before the policy step.
  const double lambda = multiplier_.update(inputs.mean_episode_cost, config().cost_limit);
  const SurrogateWeights weights = lagrangian_surrogate_weights(lambda);

  const PolicyUpdateStart start = begin_policy_update(inputs);
  const double loss_old = weighted_surrogate_loss(start.before, weights.reward, weights.cost);  // l_L(theta_old)

  // 2. g_L = -avg grad l_L = (g - lambda b) / (1 + lambda)
  const Eigen::Index num_parameters = inputs.policy.mean_net().num_parameters();
  Eigen::VectorXd lagrangian_gradient(num_parameters);
  inputs.surrogate.gradient(inputs.policy, weights.reward, weights.cost, lagrangian_gradient);
  inputs.mpi.average_in_place(lagrangian_gradient);

  // 3. x = CG(F, g_L), q = x^T F x, alpha = sqrt(2 delta / (q + 1e-8)), Delta = alpha x
  FisherVectorProduct fisher(inputs.policy, inputs.surrogate.observations(), inputs.mpi,
                             fisher_vector_product_options(config()));
  const NaturalGradientStep step = natural_gradient_step(as_linear_operator(fisher), lagrangian_gradient,
                                                         config().target_kl, conjugate_gradient_options(config()));
  // Line search A on the Lagrangian loss l_L.
  const LineSearchResult search = trpo_line_search(
      step.full_step, loss_old, surrogate_loss_evaluator(inputs, start.theta_old, weights.reward, weights.cost),
      inputs.mpi, line_search_options(config()));
  apply_line_search_result(inputs.policy, start.theta_old, search);

  PolicyUpdateResult result;
  result.diagnostics = common_diagnostics(inputs, start.before, weights.reward, weights.cost);
  append_trpo_diagnostics(result.diagnostics, search, step.step_size, lagrangian_gradient.norm(),
                          step.x_fisher_x, step.direction.norm());
  for (NamedScalar& entry : multiplier_.diagnostics()) result.diagnostics.push_back(std::move(entry));
  return result;
}

}  // namespace bsg
