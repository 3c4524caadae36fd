#include "algos/trust_region/lag_trpo.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "algos/trust_region/natural_gradient.h"
#include "algos/trust_region/trpo.h"

namespace bsg::algos {

LagTrpo::LagTrpo(const RunConfig& config)
    : OnPolicyAlgorithm(config),
      multiplier_(config) {}

std::vector<std::string> LagTrpo::diagnostic_names() const {
  std::vector<std::string> names = common_diagnostic_names();
  for (std::string& name : trpo_diagnostic_names()) names.push_back(std::move(name));
  for (std::string& name : multiplier_.diagnostic_names()) names.push_back(std::move(name));
  return names;
}

PolicyUpdateResult LagTrpo::update(const PolicyUpdateInputs& inputs) {
  check_mean_episode_cost(inputs, "lag-trpo");
  // 1. lambda_j updates (SGD by default: lambda <- max(0, lambda + alpha_lambda (J_Cj - d_j))), before the policy step.
  const std::vector<ConstraintEstimate> constraints = constraint_estimates(inputs, config());
  const ConstraintSurrogateWeights weights = lagrangian_surrogate_weights(multiplier_.update(constraints));

  const PolicyUpdateStart start = begin_policy_update(inputs);
  const double loss_old = weighted_surrogate_loss(start.before, weights.reward, weights.costs);  // l_L(theta_old)

  // 2. g_L = -avg grad l_L = (g - sum_j lambda_j b_j) / (1 + sum_j lambda_j)
  const Eigen::Index num_parameters = inputs.policy.mean_net().num_parameters();
  Eigen::VectorXd lagrangian_gradient(num_parameters);
  inputs.surrogate.gradient(inputs.policy, weights.reward, weights.costs, lagrangian_gradient);
  inputs.mpi.average_in_place(lagrangian_gradient);

  // 3. x = CG(F, g_L), q = x^T F x, alpha = sqrt(2 delta / (q + 1e-8)), Delta = alpha x
  FisherVectorProduct fisher(inputs.policy, inputs.surrogate.observations(), inputs.mpi,
                             fisher_vector_product_options(config()));
  const NaturalGradientStep step = natural_gradient_step(as_linear_operator(fisher), lagrangian_gradient,
                                                         config().target_kl, conjugate_gradient_options(config()));
  // Line search A on the Lagrangian loss l_L.
  const LineSearchResult search = trpo_line_search(
      step.full_step, loss_old, surrogate_loss_evaluator(inputs, start.theta_old, weights.reward, weights.costs),
      inputs.mpi, line_search_options(config()));
  apply_line_search_result(inputs.policy, start.theta_old, search);

  PolicyUpdateResult result;
  result.diagnostics = common_diagnostics(inputs, start.before, weights.reward, std::span<const double>(weights.costs));
  append_trpo_diagnostics(result.diagnostics, search, step.step_size, lagrangian_gradient.norm(),
                          step.x_fisher_x, step.direction.norm());
  multiplier_.append_to(result);
  return result;
}

}  // namespace bsg::algos
