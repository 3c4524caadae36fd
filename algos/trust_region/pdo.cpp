#include "algos/trust_region/pdo.h"

#include <stdexcept>
#include <string>

#include "algos/trust_region/natural_gradient.h"
#include "algos/trust_region/trpo.h"

namespace bsg::algos {

Eigen::VectorXd pdo_search_direction(const Eigen::Ref<const Eigen::VectorXd>& reward_gradient,
                                     const Eigen::Ref<const Eigen::VectorXd>& cost_gradient,
                                     double lagrange_multiplier) {
  if (reward_gradient.size() != cost_gradient.size()) {
    throw std::invalid_argument("pdo_search_direction: reward_gradient has " + std::to_string(reward_gradient.size()) +
                                " entries, cost_gradient " + std::to_string(cost_gradient.size()));
  }
  return reward_gradient - lagrange_multiplier * cost_gradient;  // p = g - lambda b
}

Pdo::Pdo(const RunConfig& config)
    : OnPolicyAlgorithm(config),
      multiplier_(config) {}

std::vector<std::string> Pdo::diagnostic_names() const {
  std::vector<std::string> names = common_diagnostic_names();
  for (std::string& name : trpo_diagnostic_names()) names.push_back(std::move(name));
  names.push_back("Misc/cost_gradient_norm");
  for (std::string& name : multiplier_.diagnostic_names()) names.push_back(std::move(name));
  return names;
}

PolicyUpdateResult Pdo::update(const PolicyUpdateInputs& inputs) {
  check_mean_episode_cost(inputs, "pdo");
  // 1. Adam (or SGD, or PID) update of lambda on J_C - d, lambda >= 0; before the policy step.
  const std::vector<ConstraintEstimate> constraints = constraint_estimates(inputs, config());
  const std::vector<double> lambdas = multiplier_.update(constraints);

  const PolicyUpdateStart start = begin_policy_update(inputs);
  const double loss_old = -start.before.reward_surrogate;  // l_R(theta_old), local

  // g and b_j; p = g - sum_j lambda_j b_j
  Eigen::VectorXd reward_gradient, direction;
  double cost_gradient_norm = 0.0;
  if (lambdas.size() == 1) {
    const PolicyGradients gradients = averaged_policy_gradients(inputs);
    direction = pdo_search_direction(gradients.reward, gradients.cost, lambdas.front());
    reward_gradient = gradients.reward;
    cost_gradient_norm = gradients.cost.norm();
  } else {
    const ConstraintGradients gradients = averaged_constraint_gradients(inputs);
    direction = gradients.reward;
    for (std::size_t j = 0; j < lambdas.size(); ++j) {
      direction -= lambdas[j] * gradients.costs.col(static_cast<Eigen::Index>(j));
    }
    reward_gradient = gradients.reward;
    cost_gradient_norm = gradients.costs.norm();  // Frobenius: sqrt(sum_j |b_j|^2)
  }

  // x = CG(F, p), q = x^T F x, alpha = sqrt(2 delta / (q + 1e-8)), Delta = alpha x
  FisherVectorProduct fisher(inputs.policy, inputs.surrogate.observations(), inputs.mpi,
                             fisher_vector_product_options(config()));
  const NaturalGradientStep step = natural_gradient_step(as_linear_operator(fisher), direction, config().target_kl,
                                                         conjugate_gradient_options(config()));

  LineSearchResult search;
  if (config().pdo_line_search) {
    // Q14: the acceptance test uses the reward-only loss l_R.
    search = trpo_line_search(step.full_step, loss_old, surrogate_loss_evaluator(inputs, start.theta_old, 1.0, 0.0),
                              inputs.mpi, line_search_options(config()));
  } else {
    search.step = step.full_step;  // the full step, as the first trial
    search.acceptance_step = 1;
  }
  apply_line_search_result(inputs.policy, start.theta_old, search);

  PolicyUpdateResult result;
  result.diagnostics = common_diagnostics(inputs, start.before, 1.0, 0.0);
  append_trpo_diagnostics(result.diagnostics, search, step.step_size, reward_gradient.norm(),
                          step.x_fisher_x, step.direction.norm());
  result.diagnostics.push_back({"Misc/cost_gradient_norm", cost_gradient_norm});
  multiplier_.append_to(result);
  return result;
}

}  // namespace bsg::algos
