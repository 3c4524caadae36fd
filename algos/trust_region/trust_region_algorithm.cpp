#include "algos/trust_region/trust_region_algorithm.h"

#include <span>
#include <utility>

#include "algos/trust_region/natural_gradient.h"

namespace bsg::algos {

std::vector<std::string> trpo_diagnostic_names() {
  std::vector<NamedScalar> columns;
  append_trpo_diagnostics(columns, LineSearchResult{}, 0.0, 0.0, 0.0, 0.0);
  return names_of(columns);
}

void append_trpo_diagnostics(std::vector<NamedScalar>& diagnostics, const LineSearchResult& search,
                             double alpha, double gradient_norm, double x_fisher_x,
                             double direction_norm) {
  diagnostics.insert(diagnostics.end(),
                     {{"Misc/AcceptanceStep", static_cast<double>(search.acceptance_step)},
                      {"Misc/Alpha", alpha},
                      {"Misc/FinalStepNorm", search.step.norm()},
                      {"Misc/gradient_norm", gradient_norm},
                      {"Misc/xHx", x_fisher_x},
                      {"Misc/H_inv_g", direction_norm}});
}

Eigen::VectorXd averaged_surrogate_gradient(const PolicyUpdateInputs& inputs, const TrustRegionSurrogate& surrogate) {
  Eigen::VectorXd gradient(inputs.policy.mean_net().num_parameters());
  if (surrogate.is_reward_only()) {
    inputs.surrogate.gradient(inputs.policy, surrogate.reward_weight, 0.0, gradient);  // g = grad L_R
  } else {
    inputs.surrogate.gradient(inputs.policy, surrogate.reward_weight, surrogate.cost_weights, gradient);
  }
  inputs.mpi.average_in_place(gradient);
  return gradient;
}

SearchDirection TrustRegionAlgorithm::search_direction(const PolicyUpdateInputs& inputs,
                                                       const TrustRegionPlan& plan) {
  SearchDirection direction;
  direction.gradient = averaged_surrogate_gradient(inputs, plan.surrogate);
  direction.logged_gradient_norm = direction.gradient.norm();
  return direction;
}

std::vector<std::string> TrustRegionAlgorithm::diagnostic_names() const {
  std::vector<std::string> names = common_diagnostic_names();
  for (std::string& name : trpo_diagnostic_names()) names.push_back(std::move(name));
  for (std::string& name : own_diagnostic_names()) names.push_back(std::move(name));
  return names;
}

namespace {

// l(theta_old) on this rank. The reward-only form is -L_R itself, as TRPO has always computed it.
double surrogate_loss(const SurrogateValues& values, const TrustRegionSurrogate& surrogate) {
  if (surrogate.is_reward_only()) return -values.reward_surrogate;  // l_R
  return weighted_surrogate_loss(values, surrogate.reward_weight, surrogate.cost_weights);
}

LossEvaluator loss_evaluator(const PolicyUpdateInputs& inputs, const Eigen::VectorXd& theta_old,
                             const TrustRegionSurrogate& surrogate) {
  if (surrogate.is_reward_only()) return surrogate_loss_evaluator(inputs, theta_old, surrogate.reward_weight, 0.0);
  return surrogate_loss_evaluator(inputs, theta_old, surrogate.reward_weight, surrogate.cost_weights);
}

std::vector<NamedScalar> surrogate_common_diagnostics(const PolicyUpdateInputs& inputs, const SurrogateValues& before,
                                                      const TrustRegionSurrogate& surrogate) {
  if (surrogate.is_reward_only()) return common_diagnostics(inputs, before, surrogate.reward_weight, 0.0);
  return common_diagnostics(inputs, before, surrogate.reward_weight, std::span<const double>(surrogate.cost_weights));
}

}  // namespace

PolicyUpdateResult TrustRegionAlgorithm::update(const PolicyUpdateInputs& inputs) {
  TrustRegionPlan plan = plan_step(inputs);
  const PolicyUpdateStart start = begin_policy_update(inputs);
  const double loss_old = surrogate_loss(start.before, plan.surrogate);  // l(theta_old), local

  SearchDirection direction = search_direction(inputs, plan);
  // x = CG(F, g_w), q = x^T F x, alpha = sqrt(2 delta / (q + 1e-8)), Delta = alpha x
  FisherVectorProduct fisher(inputs.policy, inputs.surrogate.observations(), inputs.mpi,
                             fisher_vector_product_options(config()));
  const NaturalGradientStep step =
      natural_gradient_step(as_linear_operator(fisher), direction.gradient, config().trust_region.target_kl,
                            conjugate_gradient_options(config()));

  LineSearchResult search;
  if (plan.line_search) {
    search = trpo_line_search(step.full_step, loss_old, loss_evaluator(inputs, start.theta_old, plan.surrogate),
                              inputs.mpi, line_search_options(config()));
  } else {
    search.step = step.full_step;  // the full step, as the first trial
    search.acceptance_step = 1;
  }
  apply_line_search_result(inputs.policy, start.theta_old, search);  // theta = theta_old + final step

  PolicyUpdateResult result;
  result.diagnostics = surrogate_common_diagnostics(inputs, start.before, plan.surrogate);
  append_trpo_diagnostics(result.diagnostics, search, step.step_size, direction.logged_gradient_norm,
                          step.x_fisher_x, step.direction.norm());
  for (NamedScalar& column : direction.own_columns) result.diagnostics.push_back(std::move(column));
  for (NamedScalar& column : plan.own_columns) result.diagnostics.push_back(std::move(column));
  append_own_diagnostics(result);
  return result;
}

}  // namespace bsg::algos
