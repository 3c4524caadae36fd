#include "algos/trust_region/pdo.h"

#include <stdexcept>
#include <string>

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

TrustRegionPlan Pdo::plan_step(const PolicyUpdateInputs& inputs) {
  // 1. Adam (or SGD, or PID) update of lambda on J_C - d, lambda >= 0; before the policy step.
  TrustRegionPlan plan;  // Q14: the acceptance test uses the reward-only loss l_R
  plan.lagrange_multipliers = update_multipliers(inputs);
  plan.line_search = config().trust_region.pdo_line_search;
  return plan;
}

SearchDirection Pdo::search_direction(const PolicyUpdateInputs& inputs, const TrustRegionPlan& plan) {
  // g and b_j; p = g - sum_j lambda_j b_j (no 1 / (1 + sum_j lambda_j): irrelevant for the step)
  const std::vector<double>& lambdas = plan.lagrange_multipliers;
  SearchDirection direction;
  double cost_gradient_norm = 0.0;
  if (lambdas.size() == 1) {
    const PolicyGradients gradients = averaged_policy_gradients(inputs);
    direction.gradient = pdo_search_direction(gradients.reward, gradients.cost, lambdas.front());
    direction.logged_gradient_norm = gradients.reward.norm();
    cost_gradient_norm = gradients.cost.norm();
  } else {
    const ConstraintGradients gradients = averaged_constraint_gradients(inputs);
    direction.gradient = gradients.reward;
    for (std::size_t j = 0; j < lambdas.size(); ++j) {
      direction.gradient -= lambdas[j] * gradients.costs.col(static_cast<Eigen::Index>(j));
    }
    direction.logged_gradient_norm = gradients.reward.norm();
    cost_gradient_norm = gradients.costs.norm();  // Frobenius: sqrt(sum_j |b_j|^2)
  }
  direction.own_columns.push_back({"Misc/cost_gradient_norm", cost_gradient_norm});
  return direction;
}

std::vector<std::string> Pdo::own_diagnostic_names() const {
  std::vector<std::string> names = {"Misc/cost_gradient_norm"};
  for (std::string& name : LagrangianTrustRegion::own_diagnostic_names()) names.push_back(std::move(name));
  return names;
}

}  // namespace bsg::algos
