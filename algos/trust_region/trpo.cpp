#include "algos/trust_region/trpo.h"

#include <stdexcept>
#include <string>

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

Trpo::Trpo(const RunConfig& config) : OnPolicyAlgorithm(config) {}

std::vector<std::string> Trpo::diagnostic_names() const {
  std::vector<std::string> names = common_diagnostic_names();
  for (std::string& name : trpo_diagnostic_names()) names.push_back(std::move(name));
  return names;
}

PolicyUpdateResult Trpo::update(const PolicyUpdateInputs& inputs) {
  const PolicyUpdateStart start = begin_policy_update(inputs);
  const double loss_old = -start.before.reward_surrogate;  // l_old = l_R(theta_old), local

  // g = avg grad L_R (= -avg grad l_R)
  const Eigen::Index num_parameters = inputs.policy.mean_net().num_parameters();
  Eigen::VectorXd reward_gradient(num_parameters);
  inputs.surrogate.gradient(inputs.policy, 1.0, 0.0, reward_gradient);
  inputs.mpi.average_in_place(reward_gradient);

  FisherVectorProduct fisher(inputs.policy, inputs.surrogate.observations(), inputs.mpi,
                             fisher_vector_product_options(config()));
  // x = CG(F, g), q = x^T F x, alpha = sqrt(2 delta / (q + 1e-8)), Delta = alpha x
  const NaturalGradientStep step = natural_gradient_step(as_linear_operator(fisher), reward_gradient,
                                                         config().target_kl, conjugate_gradient_options(config()));

  const LineSearchResult search =
      trpo_line_search(step.full_step, loss_old, surrogate_loss_evaluator(inputs, start.theta_old, 1.0, 0.0),
                       inputs.mpi, line_search_options(config()));
  apply_line_search_result(inputs.policy, start.theta_old, search);  // theta = theta_old + final step

  PolicyUpdateResult result;
  result.diagnostics = common_diagnostics(inputs, start.before, 1.0, 0.0);
  append_trpo_diagnostics(result.diagnostics, search, step.step_size, reward_gradient.norm(),
                          step.x_fisher_x, step.direction.norm());
  return result;
}

}  // namespace bsg::algos
