#include "algos/trust_region/cpo.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "algos/core/constraint_costs.h"
#include "algos/trust_region/constraint_qp.h"
#include "algos/trust_region/natural_gradient.h"
#include "algos/trust_region/trust_region_algorithm.h"

namespace bsg::algos {
namespace {

constexpr double kEpsilon = 1e-8;  // every epsilon of docs/algorithms.md#cpo, step 7

// Pi(t; lo, hi) = max(lo, min(t, hi)); lo > hi gives lo, as the original (np.clip-like).
double project_onto_interval(double t, double lo, double hi) { return std::max(lo, std::min(t, hi)); }

std::string describe(const CpoStep& step, double c) {
  return "q=" + std::to_string(step.q) + " r=" + std::to_string(step.r) + " s=" + std::to_string(step.s) +
         " A=" + std::to_string(step.A) + " B=" + std::to_string(step.B) + " c=" + std::to_string(c);
}

}  // namespace

void append_cpo_diagnostics(std::vector<NamedScalar>& diagnostics, const CpoColumns& columns) {
  diagnostics.insert(diagnostics.end(), {{"Misc/cost_gradient_norm", columns.cost_gradient_norm},
                                         {"Misc/A", columns.A},
                                         {"Misc/B", columns.B},
                                         {"Misc/q", columns.q},
                                         {"Misc/r", columns.r},
                                         {"Misc/s", columns.s},
                                         {"Misc/Lambda_star", columns.lambda_star},
                                         {"Misc/Nu_star", columns.nu_star},
                                         {"Misc/OptimCase", columns.optim_case}});
}

std::vector<std::string> cpo_diagnostic_names() {
  std::vector<NamedScalar> columns;
  append_cpo_diagnostics(columns, CpoColumns{});
  return names_of(columns);
}

CpoStep cpo_step(const LinearOperator& fisher, const Eigen::Ref<const Eigen::VectorXd>& reward_gradient,
                 const Eigen::Ref<const Eigen::VectorXd>& cost_gradient, double constraint_violation,
                 const CpoStepOptions& options) {
  if (reward_gradient.size() != cost_gradient.size()) {
    throw std::invalid_argument("cpo_step: reward_gradient has " + std::to_string(reward_gradient.size()) +
                                " entries, cost_gradient " + std::to_string(cost_gradient.size()));
  }
  if (!std::isfinite(constraint_violation)) {
    throw std::invalid_argument("cpo_step: constraint_violation c is not finite: " +
                                std::to_string(constraint_violation));
  }
  const double c = constraint_violation;
  const double delta = options.target_kl;
  const auto& g = reward_gradient;
  const auto& b = cost_gradient;

  CpoStep step;
  // x = CG(F, g), q = x^T F x, alpha_T = sqrt(2 delta / (q + 1e-8))
  const NaturalGradientStep natural = natural_gradient_step(fisher, g, delta, options.conjugate_gradient);
  step.reward_direction = natural.direction;
  step.q = natural.x_fisher_x;
  step.trpo_step_size = natural.step_size;
  const Eigen::VectorXd& x = step.reward_direction;

  step.cost_direction = conjugate_gradient(fisher, b, options.conjugate_gradient).solution;  // p = CG(F, b)
  const Eigen::VectorXd& p = step.cost_direction;
  step.r = g.dot(p);  // r = g^T p ~ g^T F^-1 b
  step.s = b.dot(p);  // s = b^T p ~ b^T F^-1 b
  const double q = step.q;
  const double s = step.s;

  if (b.squaredNorm() <= 1e-6 && c < 0.0) {
    step.optim_case = CpoCase::negligible_cost_gradient;  // A = B = 0
  } else {
    step.A = q - step.r * step.r / s;          // A = q - r^2 / s
    step.B = 2.0 * delta - c * c / s;          // B = 2 delta - c^2 / s
    if (c < 0.0) {
      step.optim_case = step.B < 0.0 ? CpoCase::region_feasible : CpoCase::constraint_cuts_region;
    } else {
      step.optim_case = step.B < 0.0 ? CpoCase::infeasible_recovery : CpoCase::feasible_recovery;
    }
  }

  switch (step.optim_case) {
    case CpoCase::region_feasible:
    case CpoCase::negligible_cost_gradient: {
      // TRPO step: lambda* = 1/alpha_T, nu* = 0, Delta = alpha_T x
      step.lambda_star = 1.0 / step.trpo_step_size;
      step.nu_star = 0.0;
      step.full_step = step.trpo_step_size * x;
      break;
    }
    case CpoCase::feasible_recovery:
    case CpoCase::constraint_cuts_region: {
      // Q10: the original uses r = g^T p in the dual; the corrected dual uses -g^T p.
      const double r = options.r_sign == CpoRSign::corrected ? -step.r : step.r;
      double A = step.A;
      const double B = step.B;
      if (A < 0.0) {
        if (!options.clamp_a) {
          throw std::runtime_error("cpo_step: A = q - r^2/s is negative (" + describe(step, c) +
                                   "), so sqrt(A/B) is not defined; set cpo_clamp_a: true to clamp A at 0");
        }
        A = 0.0;
        step.A = 0.0;
      }
      const double lambda_a = std::sqrt(A / B);             // lambda_a = sqrt(A/B)
      const double lambda_b = std::sqrt(q / (2.0 * delta));  // lambda_b = sqrt(q / (2 delta))
      if (!std::isfinite(lambda_a)) {
        throw std::runtime_error("cpo_step: sqrt(A/B) is not finite (" + describe(step, c) + ")");
      }
      const double boundary = r / c;  // r/c (IEEE: c = 0 gives +-inf)
      const double infinity = std::numeric_limits<double>::infinity();
      double lambda_a_star = 0.0;
      double lambda_b_star = 0.0;
      if (c < 0.0) {
        lambda_a_star = project_onto_interval(lambda_a, 0.0, boundary);
        lambda_b_star = project_onto_interval(lambda_b, boundary, infinity);
      } else {
        lambda_a_star = project_onto_interval(lambda_a, boundary, infinity);
        lambda_b_star = project_onto_interval(lambda_b, 0.0, boundary);
      }
      // f_a(l) = -1/2 (A/(l+eps) + B l) - r c/(s+eps);  f_b(l) = -1/2 (q/(l+eps) + 2 delta l)
      const double f_a = -0.5 * (A / (lambda_a_star + kEpsilon) + B * lambda_a_star) - r * c / (s + kEpsilon);
      const double f_b = -0.5 * (q / (lambda_b_star + kEpsilon) + 2.0 * delta * lambda_b_star);
      step.lambda_star = f_a >= f_b ? lambda_a_star : lambda_b_star;
      step.nu_star = std::max(step.lambda_star * c - r, 0.0) / (s + kEpsilon);  // nu* = (lambda* c - r)_+ / (s + eps)
      step.full_step = (x - step.nu_star * p) / (step.lambda_star + kEpsilon);   // Delta = (x - nu* p) / (lambda* + eps)
      break;
    }
    case CpoCase::infeasible_recovery: {
      // Pure cost decrease: lambda* = 0, nu* = sqrt(2 delta / (s + eps)), Delta = -nu* p
      step.lambda_star = 0.0;
      step.nu_star = std::sqrt(2.0 * delta / (s + kEpsilon));
      step.full_step = -step.nu_star * p;
      break;
    }
  }
  if (!step.full_step.allFinite()) {
    throw std::runtime_error("cpo_step: the step of case " + std::to_string(static_cast<int>(step.optim_case)) +
                             " is not finite (" + describe(step, c) + ")");
  }
  return step;
}

Eigen::MatrixXd conjugate_gradient_columns(const LinearOperator& fisher, const Eigen::Ref<const Eigen::MatrixXd>& costs,
                                           const ConjugateGradientOptions& options) {
  Eigen::MatrixXd directions(costs.rows(), costs.cols());
  for (Eigen::Index j = 0; j < costs.cols(); ++j) {
    directions.col(j) = conjugate_gradient(fisher, costs.col(j), options).solution;  // p_j = CG(F, b_j)
  }
  return directions;
}

std::vector<std::string> constraint_multiplier_names(int constraint_count) {
  std::vector<std::string> names;
  for (int j = 1; j <= constraint_count; ++j) names.push_back("constraint_" + std::to_string(j) + "_nu");
  return names;
}

Cpo::Cpo(const RunConfig& config) : OnPolicyAlgorithm(config) {}

std::vector<std::string> Cpo::diagnostic_names() const {
  std::vector<std::string> names = common_diagnostic_names();
  for (std::string& name : trpo_diagnostic_names()) names.push_back(std::move(name));
  if (constraint_count(config()) == 1) {
    for (std::string& name : cpo_diagnostic_names()) names.push_back(std::move(name));
    return names;
  }
  for (const char* name : {"Misc/cost_gradient_norm", "Misc/q", "Misc/Lambda_star", "Misc/OptimCase"}) {
    names.emplace_back(name);
  }
  for (std::string& name : constraint_multiplier_names(constraint_count(config()))) names.push_back(std::move(name));
  return names;
}

SeveralConstraintsStart begin_several_constraints_update(const PolicyUpdateInputs& inputs,
                                                         const std::vector<ConstraintEstimate>& constraints,
                                                         const RunConfig& config) {
  SeveralConstraintsStart begun;
  begun.fisher_product = std::make_unique<FisherVectorProduct>(
      inputs.policy, inputs.surrogate.observations(), inputs.mpi, fisher_vector_product_options(config));
  begun.fisher = as_linear_operator(*begun.fisher_product);
  begun.violations = per_step_constraint_violations(constraints, inputs.mean_episode_length);  // c_j
  begun.start = begin_policy_update(inputs);
  begun.gradients = averaged_constraint_gradients(inputs);  // g, B
  begun.natural = natural_gradient_step(begun.fisher, begun.gradients.reward, config.trust_region.target_kl,
                                        conjugate_gradient_options(config));  // x, q, eta, Delta_R
  return begun;
}

std::vector<NamedScalar> several_constraints_diagnostics(const PolicyUpdateInputs& inputs,
                                                         const SeveralConstraintsStart& begun,
                                                         const LineSearchResult& search,
                                                         const std::vector<NamedScalar>& extra,
                                                         const Eigen::VectorXd& nu) {
  std::vector<NamedScalar> diagnostics = common_diagnostics(inputs, begun.start.before, 1.0, 0.0);
  append_trpo_diagnostics(diagnostics, search, begun.natural.step_size, begun.gradients.reward.norm(),
                          begun.natural.x_fisher_x, begun.natural.direction.norm());
  diagnostics.push_back({"Misc/cost_gradient_norm", begun.gradients.costs.norm()});  // Frobenius
  diagnostics.push_back({"Misc/q", begun.natural.x_fisher_x});
  diagnostics.insert(diagnostics.end(), extra.begin(), extra.end());
  const std::vector<std::string> nu_names = constraint_multiplier_names(static_cast<int>(nu.size()));
  for (Eigen::Index j = 0; j < nu.size(); ++j) diagnostics.push_back({nu_names[static_cast<std::size_t>(j)], nu[j]});
  return diagnostics;
}

PolicyUpdateResult Cpo::update_several(const PolicyUpdateInputs& inputs,
                                       const std::vector<ConstraintEstimate>& constraints) {
  const SeveralConstraintsStart begun = begin_several_constraints_update(inputs, constraints, config());
  const Eigen::MatrixXd P =
      conjugate_gradient_columns(begun.fisher, begun.gradients.costs, conjugate_gradient_options(config()));  // p_j
  const Eigen::VectorXd r = P.transpose() * begun.gradients.reward;  // r_j = g^T p_j
  const Eigen::MatrixXd S = begun.gradients.costs.transpose() * P;   // S_jk = b_j^T p_k
  const CpoDualSolution dual =
      solve_cpo_dual(begun.natural.x_fisher_x, r, S, begun.violations, config().trust_region.target_kl);
  // Delta = (x - sum_j nu_j p_j) / lambda*; infeasible: -sum_j nu_j p_j scaled to the trust region.
  const Eigen::VectorXd full_step =
      dual.direction_scale * (dual.reward_weight * begun.natural.direction - P * dual.nu);
  if (!full_step.allFinite()) {
    throw std::runtime_error("cpo: the step with " + std::to_string(constraints.size()) +
                             " constraints is not finite (q=" + std::to_string(begun.natural.x_fisher_x) + ")");
  }
  const LineSearchResult search = constrained_line_search_all(inputs, begun.start, full_step, begun.violations,
                                                              starts_feasible(dual.optim_case), config());
  apply_line_search_result(inputs.policy, begun.start.theta_old, search);

  PolicyUpdateResult result;
  result.diagnostics = several_constraints_diagnostics(
      inputs, begun, search,
      {{"Misc/Lambda_star", dual.lambda}, {"Misc/OptimCase", static_cast<double>(dual.optim_case)}}, dual.nu);
  return result;
}

SingleConstraintCpoUpdate single_constraint_cpo_update(const PolicyUpdateInputs& inputs, double constraint_violation,
                                                       const RunConfig& config) {
  const double c = constraint_violation;
  SingleConstraintCpoUpdate update;
  update.start = begin_policy_update(inputs);               // l_R(theta_old), L_C(theta_old)
  update.gradients = averaged_policy_gradients(inputs);     // g, b

  FisherVectorProduct fisher(inputs.policy, inputs.surrogate.observations(), inputs.mpi,
                             fisher_vector_product_options(config));
  CpoStepOptions step_options;
  step_options.target_kl = config.trust_region.target_kl;
  step_options.r_sign = config.trust_region.cpo_r_sign;
  step_options.clamp_a = config.trust_region.cpo_clamp_a;
  step_options.conjugate_gradient = conjugate_gradient_options(config);
  update.step = cpo_step(as_linear_operator(fisher), update.gradients.reward, update.gradients.cost, c, step_options);

  // Line search B; the reward test only where the current policy is feasible (cases 2, 3, 4).
  ConstrainedLineSearchInputs search_inputs;
  search_inputs.reward_loss_old = -update.start.before.reward_surrogate;
  search_inputs.cost_surrogate_old = update.start.before.cost_surrogate;
  search_inputs.constraint_violation = c;
  search_inputs.require_reward_improvement = starts_feasible(update.step.optim_case);
  update.search = constrained_line_search(update.step.full_step, search_inputs,
                                          constrained_evaluator(inputs, update.start.theta_old), inputs.mpi,
                                          line_search_options(config));
  apply_line_search_result(inputs.policy, update.start.theta_old, update.search);
  return update;
}

std::vector<NamedScalar> single_constraint_cpo_diagnostics(const PolicyUpdateInputs& inputs,
                                                           const SingleConstraintCpoUpdate& update) {
  const CpoStep& step = update.step;
  std::vector<NamedScalar> diagnostics = common_diagnostics(inputs, update.start.before, 1.0, 0.0);
  append_trpo_diagnostics(diagnostics, update.search, step.trpo_step_size, update.gradients.reward.norm(), step.q,
                          step.reward_direction.norm());
  append_cpo_diagnostics(diagnostics, {.cost_gradient_norm = update.gradients.cost.norm(),
                                       .A = step.A,
                                       .B = step.B,
                                       .q = step.q,
                                       .r = step.r,
                                       .s = step.s,
                                       .lambda_star = step.lambda_star,
                                       .nu_star = step.nu_star,
                                       .optim_case = static_cast<double>(step.optim_case)});
  return diagnostics;
}

PolicyUpdateResult Cpo::update(const PolicyUpdateInputs& inputs) {
  const std::vector<ConstraintEstimate> constraints = constraint_estimates(inputs, config());
  if (constraints.size() > 1) return update_several(inputs, constraints);
  const double c = per_step_constraint_violation(constraints.front().mean_episode_cost, inputs.mean_episode_length,
                                                 constraints.front().limit);  // c = (J_C - d) / (L + 1e-8)
  const SingleConstraintCpoUpdate update = single_constraint_cpo_update(inputs, c, config());
  PolicyUpdateResult result;
  result.diagnostics = single_constraint_cpo_diagnostics(inputs, update);
  return result;
}

}  // namespace bsg::algos
