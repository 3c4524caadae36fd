#include "algos/core/algorithm.h"

#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

namespace bsg::algos {

double PolicyUpdateResult::value(std::string_view name) const {
  for (const NamedScalar& entry : diagnostics) {
    if (entry.name == name) return entry.value;
  }
  throw std::out_of_range("PolicyUpdateResult::value: no diagnostic named '" + std::string(name) + "'");
}

std::vector<std::string> names_of(std::span<const NamedScalar> columns) {
  std::vector<std::string> names;
  names.reserve(columns.size());
  for (const NamedScalar& column : columns) names.push_back(column.name);
  return names;
}

std::vector<std::string> common_diagnostic_names() {
  return {kCommonDiagnosticNames.begin(), kCommonDiagnosticNames.end()};
}

std::vector<ConstraintEstimate> constraint_estimates(const PolicyUpdateInputs& inputs, const RunConfig& config) {
  if (inputs.constraints.empty()) return {ConstraintEstimate{inputs.mean_episode_cost, config.cost_limit}};
  if (static_cast<int>(inputs.constraints.size()) != inputs.surrogate.constraint_count()) {
    throw std::invalid_argument("constraint_estimates: " + std::to_string(inputs.constraints.size()) +
                                " constraints, but the surrogate holds " +
                                std::to_string(inputs.surrogate.constraint_count()) + " cost advantages");
  }
  for (std::size_t i = 0; i < inputs.constraints.size(); ++i) {
    if (!std::isfinite(inputs.constraints[i].mean_episode_cost)) {
      throw std::invalid_argument("constraint " + std::to_string(i + 1) + ": mean episode cost J_C" +
                                  std::to_string(i + 1) + " is not finite (no episode completed this epoch?)");
    }
  }
  return {inputs.constraints.begin(), inputs.constraints.end()};
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
  return weighted_surrogate_loss(values, reward_weight, std::span<const double>(&cost_weight, 1));
}

double weighted_surrogate_loss(const SurrogateValues& values, double reward_weight,
                               std::span<const double> cost_weights) {
  double weighted = reward_weight * values.reward_surrogate;
  for (std::size_t j = 0; j < cost_weights.size(); ++j) weighted += cost_weights[j] * values.cost_surrogates[j];
  return -weighted;
}

std::vector<NamedScalar> common_diagnostics(const PolicyUpdateInputs& inputs, const SurrogateValues& before,
                                            double reward_weight, std::span<const double> cost_weights) {
  const SurrogateValues after = inputs.surrogate.evaluate(inputs.policy);
  const double loss_before = weighted_surrogate_loss(before, reward_weight, cost_weights);
  const double loss_after = weighted_surrogate_loss(after, reward_weight, cost_weights);
  const std::array<double, kCommonDiagnosticCount> values = {
      loss_before, loss_after - loss_before, inputs.policy.entropy_per_dimension(), after.kl, after.mean_ratio};
  std::vector<NamedScalar> diagnostics;
  for (std::size_t i = 0; i < kCommonDiagnosticCount; ++i) {
    diagnostics.push_back({std::string(kCommonDiagnosticNames[i]), values[i]});
  }
  return diagnostics;
}

std::vector<NamedScalar> common_diagnostics(const PolicyUpdateInputs& inputs, const SurrogateValues& before,
                                            double reward_weight, double cost_weight) {
  return common_diagnostics(inputs, before, reward_weight, std::span<const double>(&cost_weight, 1));
}

void OnPolicyAlgorithm::restore_state(std::span<const NamedScalar> saved) {
  if (!saved.empty()) {
    throw std::invalid_argument(std::string(name()) + ": restore_state expects an empty state, got " +
                                std::to_string(saved.size()) + " values (first '" + saved.front().name + "')");
  }
}

}  // namespace bsg::algos
