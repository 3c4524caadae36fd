#include "algos/trust_region/pcpo.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "algos/core/constraint_costs.h"
#include "algos/trust_region/constraint_qp.h"
#include "algos/trust_region/cpo.h"
#include "algos/trust_region/natural_gradient.h"
#include "algos/trust_region/trust_region_algorithm.h"

namespace bsg::algos {

PcpoStep pcpo_step(const LinearOperator& fisher, const Eigen::Ref<const Eigen::VectorXd>& reward_gradient,
                   const Eigen::Ref<const Eigen::VectorXd>& cost_gradient, double constraint_violation,
                   const PcpoStepOptions& options) {
  if (reward_gradient.size() != cost_gradient.size()) {
    throw std::invalid_argument("pcpo_step: reward_gradient has " + std::to_string(reward_gradient.size()) +
                                " entries, cost_gradient " + std::to_string(cost_gradient.size()));
  }
  if (!std::isfinite(constraint_violation)) {
    throw std::invalid_argument("pcpo_step: constraint_violation c is not finite: " +
                                std::to_string(constraint_violation));
  }
  const double c = constraint_violation;
  const auto& b = cost_gradient;

  PcpoStep step;
  // x = CG(F, g), q = x^T F x, eta = sqrt(2 delta / (q + 1e-8)), Delta_R = eta x
  const NaturalGradientStep natural =
      natural_gradient_step(fisher, reward_gradient, options.target_kl, options.conjugate_gradient);
  step.reward_direction = natural.direction;
  step.q = natural.x_fisher_x;
  step.eta = natural.step_size;
  step.reward_step = natural.full_step;
  step.r = b.dot(step.reward_direction);                  // b^T x ~ a^T H^-1 g
  step.violation_after_reward_step = c + step.eta * step.r;  // v = c + b^T Delta_R

  if (options.projection == PcpoProjection::kl) {
    step.projection_direction = conjugate_gradient(fisher, b, options.conjugate_gradient).solution;  // p = CG(F, b)
  } else {
    step.projection_direction = b;  // L^-1 a with L = I
  }
  step.s = b.dot(step.projection_direction);  // a^T L^-1 a
  if (b.squaredNorm() > 1e-6) {
    step.nu = std::max(0.0, step.violation_after_reward_step) / (step.s + 1e-8);  // nu = max(0, v) / (s + eps)
  }
  step.full_step = step.reward_step - step.nu * step.projection_direction;  // Delta = Delta_R - nu L^-1 a
  if (!step.full_step.allFinite()) {
    throw std::runtime_error("pcpo_step: the projected step is not finite (q=" + std::to_string(step.q) +
                             " s=" + std::to_string(step.s) + " v=" +
                             std::to_string(step.violation_after_reward_step) + ")");
  }
  return step;
}

Pcpo::Pcpo(const RunConfig& config) : OnPolicyAlgorithm(config) {}

std::vector<std::string> Pcpo::diagnostic_names() const {
  std::vector<std::string> names = common_diagnostic_names();
  for (std::string& name : trpo_diagnostic_names()) names.push_back(std::move(name));
  if (constraint_count(config()) == 1) {
    for (std::string& name : cpo_diagnostic_names()) names.push_back(std::move(name));
    return names;
  }
  for (const char* name : {"Misc/cost_gradient_norm", "Misc/q", "Misc/OptimCase"}) names.emplace_back(name);
  for (std::string& name : constraint_multiplier_names(constraint_count(config()))) names.push_back(std::move(name));
  return names;
}

PolicyUpdateResult Pcpo::update_several(const PolicyUpdateInputs& inputs,
                                        const std::vector<ConstraintEstimate>& constraints) {
  const SeveralConstraintsStart begun = begin_several_constraints_update(inputs, constraints, config());
  const Eigen::MatrixXd& B = begun.gradients.costs;
  const Eigen::VectorXd& c = begun.violations;
  const Eigen::Index m = B.cols();
  // L^-1 b_j: CG(F, b_j) in the KL metric, b_j itself in L2.
  const Eigen::MatrixXd directions = config().trust_region.pcpo_projection == PcpoProjection::kl
                                         ? conjugate_gradient_columns(begun.fisher, B, conjugate_gradient_options(config()))
                                         : B;
  // Only constraints with a usable gradient take part (the single constraint's b^T b > 1e-6 guard).
  std::vector<Eigen::Index> used;
  for (Eigen::Index j = 0; j < m; ++j) {
    if (B.col(j).squaredNorm() > 1e-6) used.push_back(j);
  }
  Eigen::VectorXd mu = Eigen::VectorXd::Zero(m);
  if (!used.empty()) {
    const Eigen::Index k = static_cast<Eigen::Index>(used.size());
    Eigen::MatrixXd S(k, k);
    Eigen::VectorXd v(k);
    for (Eigen::Index a = 0; a < k; ++a) {
      const Eigen::Index j = used[static_cast<std::size_t>(a)];
      v[a] = c[j] + B.col(j).dot(begun.natural.full_step);  // v_j = c_j + b_j^T Delta_R
      for (Eigen::Index b = 0; b < k; ++b) {
        S(a, b) = B.col(j).dot(directions.col(used[static_cast<std::size_t>(b)]));  // b_j^T L^-1 b_k
      }
    }
    const Eigen::VectorXd weights = nonnegative_projection_weights(S, v);
    for (Eigen::Index a = 0; a < k; ++a) mu[used[static_cast<std::size_t>(a)]] = weights[a];
  }
  const Eigen::VectorXd full_step = begun.natural.full_step - directions * mu;  // Delta = Delta_R - sum_j mu_j L^-1 b_j
  if (!full_step.allFinite()) {
    throw std::runtime_error("pcpo: the projected step with " + std::to_string(m) + " constraints is not finite");
  }

  LineSearchResult search;
  if (config().trust_region.pcpo_line_search) {
    search = constrained_line_search_all(inputs, begun.start, full_step, c, (c.array() < 0.0).all(), config());
  } else {
    search.step = full_step;  // the paper's release: apply Delta directly
    search.acceptance_step = 1;
  }
  apply_line_search_result(inputs.policy, begun.start.theta_old, search);

  PolicyUpdateResult result;
  result.diagnostics = several_constraints_diagnostics(
      inputs, begun, search, {{"Misc/OptimCase", (c.array() >= 0.0).any() ? 1.0 : 2.0}}, mu);
  return result;
}

PolicyUpdateResult Pcpo::update(const PolicyUpdateInputs& inputs) {
  const std::vector<ConstraintEstimate> constraints = constraint_estimates(inputs, config());
  if (constraints.size() > 1) return update_several(inputs, constraints);
  const double c = per_step_constraint_violation(constraints.front().mean_episode_cost, inputs.mean_episode_length,
                                                 constraints.front().limit);  // c = (J_C - d) / (L + 1e-8)
  const PolicyUpdateStart start = begin_policy_update(inputs);
  const PolicyGradients gradients = averaged_policy_gradients(inputs);  // g, b

  FisherVectorProduct fisher(inputs.policy, inputs.surrogate.observations(), inputs.mpi,
                             fisher_vector_product_options(config()));
  PcpoStepOptions step_options;
  step_options.target_kl = config().trust_region.target_kl;
  step_options.projection = config().trust_region.pcpo_projection;
  step_options.conjugate_gradient = conjugate_gradient_options(config());
  const PcpoStep step = pcpo_step(as_linear_operator(fisher), gradients.reward, gradients.cost, c, step_options);

  LineSearchResult search;
  if (config().trust_region.pcpo_line_search) {
    ConstrainedLineSearchInputs search_inputs;
    search_inputs.reward_loss_old = -start.before.reward_surrogate;
    search_inputs.cost_surrogate_old = start.before.cost_surrogate;
    search_inputs.constraint_violation = c;
    search_inputs.require_reward_improvement = c < 0.0;  // the analogue of CPO cases >= 2
    search = constrained_line_search(step.full_step, search_inputs, constrained_evaluator(inputs, start.theta_old),
                                     inputs.mpi, line_search_options(config()));
  } else {
    search.step = step.full_step;  // the paper's release: apply Delta directly
    search.acceptance_step = 1;
  }
  apply_line_search_result(inputs.policy, start.theta_old, search);

  PolicyUpdateResult result;
  result.diagnostics = common_diagnostics(inputs, start.before, 1.0, 0.0);
  append_trpo_diagnostics(result.diagnostics, search, step.eta, gradients.reward.norm(),
                          step.q, step.reward_direction.norm());
  // A, B and lambda* are not defined for PCPO: 0.
  append_cpo_diagnostics(result.diagnostics, {.cost_gradient_norm = gradients.cost.norm(),
                                               .q = step.q,
                                               .r = step.r,
                                               .s = step.s,
                                               .nu_star = step.nu,
                                               .optim_case = c >= 0.0 ? 1.0 : 2.0});
  return result;
}

}  // namespace bsg::algos
