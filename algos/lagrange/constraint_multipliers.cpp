#include "algos/lagrange/constraint_multipliers.h"

#include <map>
#include <stdexcept>
#include <utility>

#include "algos/core/constraint_costs.h"

namespace bsg::algos {
namespace {

std::string column_name(int i, const std::string& diagnostic) {
  static const std::map<std::string, std::string> kSuffix = {
      {"LagrangeMultiplier", "lambda"}, {"PID/P", "pid_p"}, {"PID/I", "pid_i"}, {"PID/D", "pid_d"}};
  const auto found = kSuffix.find(diagnostic);
  return "constraint_" + std::to_string(i + 1) + "_" + (found == kSuffix.end() ? diagnostic : found->second);
}

std::string state_prefix(int i) { return "constraint_" + std::to_string(i + 1) + "/"; }

}  // namespace

LagrangeMultipliers::LagrangeMultipliers(const RunConfig& config) {
  const int m = constraint_count(config);
  multipliers_.reserve(static_cast<std::size_t>(m));
  for (int i = 0; i < m; ++i) multipliers_.emplace_back(config);
}

std::vector<double> LagrangeMultipliers::update(std::span<const ConstraintEstimate> constraints) {
  if (static_cast<int>(constraints.size()) != count()) {
    throw std::invalid_argument("LagrangeMultipliers::update: " + std::to_string(constraints.size()) +
                                " constraints for " + std::to_string(count()) + " multipliers");
  }
  std::vector<double> lambdas;
  for (std::size_t i = 0; i < multipliers_.size(); ++i) {
    lambdas.push_back(multipliers_[i].update(constraints[i].mean_episode_cost, constraints[i].limit));
  }
  return lambdas;
}

std::vector<double> LagrangeMultipliers::update(const PolicyUpdateInputs& inputs, const RunConfig& config,
                                                std::string_view algorithm) {
  check_mean_episode_cost(inputs, algorithm);
  return update(constraint_estimates(inputs, config));
}

void LagrangeMultipliers::append_diagnostic_names(std::vector<std::string>& names) const {
  for (std::string& name : diagnostic_names()) names.push_back(std::move(name));
}

std::vector<std::string> LagrangeMultipliers::diagnostic_names() const {
  std::vector<std::string> names;
  for (NamedScalar& entry : diagnostics()) names.push_back(std::move(entry.name));
  return names;
}

void LagrangeMultipliers::append_to(PolicyUpdateResult& result) const {
  for (NamedScalar& entry : diagnostics()) result.diagnostics.push_back(std::move(entry));
  if (count() == 1) result.lagrange_multiplier = value(0);
}

std::vector<NamedScalar> LagrangeMultipliers::diagnostics() const {
  if (count() == 1) return multipliers_.front().diagnostics();
  std::vector<NamedScalar> values;
  for (int i = 0; i < count(); ++i) {
    for (const NamedScalar& entry : multipliers_[static_cast<std::size_t>(i)].diagnostics()) {
      values.push_back({column_name(i, entry.name), entry.value});
    }
  }
  return values;
}

std::vector<NamedScalar> LagrangeMultipliers::state() const {
  if (count() == 1) return multipliers_.front().state();
  std::vector<NamedScalar> saved;
  for (int i = 0; i < count(); ++i) {
    for (const NamedScalar& entry : multipliers_[static_cast<std::size_t>(i)].state()) {
      saved.push_back({state_prefix(i) + entry.name, entry.value});
    }
  }
  return saved;
}

void LagrangeMultipliers::restore_state(std::span<const NamedScalar> saved) {
  if (count() == 1) {
    multipliers_.front().restore_state(saved);
    return;
  }
  const std::vector<NamedScalar> expected = state();
  if (saved.size() != expected.size()) {
    throw std::invalid_argument("LagrangeMultipliers::restore_state: expected " + std::to_string(expected.size()) +
                                " values for " + std::to_string(count()) + " multipliers, got " +
                                std::to_string(saved.size()));
  }
  // Validate every multiplier's part on a copy first, so a bad entry changes nothing.
  std::vector<LagrangeMultiplier> restored = multipliers_;
  std::size_t offset = 0;
  for (int i = 0; i < count(); ++i) {
    const std::size_t size = multipliers_[static_cast<std::size_t>(i)].state().size();
    std::vector<NamedScalar> part;
    for (std::size_t k = 0; k < size; ++k) {
      const NamedScalar& entry = saved[offset + k];
      const std::string prefix = state_prefix(i);
      if (entry.name.rfind(prefix, 0) != 0) {
        throw std::invalid_argument("LagrangeMultipliers::restore_state: entry '" + entry.name + "', expected '" +
                                    expected[offset + k].name + "'");
      }
      part.push_back({entry.name.substr(prefix.size()), entry.value});
    }
    restored[static_cast<std::size_t>(i)].restore_state(part);
    offset += size;
  }
  multipliers_ = std::move(restored);
}

}  // namespace bsg::algos
