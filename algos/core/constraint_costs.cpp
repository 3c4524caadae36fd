#include "algos/core/constraint_costs.h"

#include <algorithm>
#include <stdexcept>

#include "common/config_error.h"
#include "common/message_text.h"

namespace bsg::algos {

int constraint_count(const RunConfig& config) {
  return config.constraints.empty() ? 1 : static_cast<int>(config.constraints.size());
}

double constraint_limit(const RunConfig& config, int i) {
  if (config.constraints.empty()) return config.cost_limit;
  return config.constraints.at(static_cast<std::size_t>(i)).limit;
}

std::vector<ConstraintConfig> effective_constraints(const RunConfig& config) {
  if (!config.constraints.empty()) return config.constraints;
  return {ConstraintConfig{{std::string(kAllCostTerms)}, config.cost_limit}};
}

StepCostSelector::StepCostSelector()
    : constraints_{ConstraintConfig{{std::string(kAllCostTerms)}, 0.0}}, positions_(1) {}

StepCostSelector::StepCostSelector(const RunConfig& config)
    : constraints_(effective_constraints(config)), positions_(constraints_.size()) {}

bool StepCostSelector::needs_terms() const {
  return std::any_of(constraints_.begin(), constraints_.end(),
                     [](const ConstraintConfig& c) { return !c.sums_all_terms(); });
}

void StepCostSelector::bind(const std::vector<std::string>& term_names, const std::string& env_id) {
  for (std::size_t i = 0; i < constraints_.size(); ++i) {
    positions_[i].clear();
    if (constraints_[i].sums_all_terms()) continue;
    for (const std::string& term : constraints_[i].terms) {
      const auto found = std::find(term_names.begin(), term_names.end(), term);
      if (found == term_names.end()) {
        const std::string list = comma_separated(term_names);
        throw ConfigError("key 'constraints': constraint " + std::to_string(i + 1) + " names the cost term '" + term +
                          "', which " + env_id + " does not have; its terms: " + list + " (or all)");
      }
      positions_[i].push_back(static_cast<std::size_t>(found - term_names.begin()));
    }
  }
  term_count_ = term_names.size();
  bound_ = true;
}

void StepCostSelector::select(const envs::StepResult& step, Eigen::Ref<Eigen::VectorXd> costs) const {
  if (costs.size() != count()) {
    throw std::invalid_argument("StepCostSelector::select: " + std::to_string(costs.size()) + " outputs for " +
                                std::to_string(count()) + " constraints");
  }
  const bool terms_needed = needs_terms();
  if (terms_needed && (!bound_ || step.cost_terms.size() != term_count_)) {
    throw std::logic_error("StepCostSelector::select: the cost terms are not bound to this environment's " +
                           std::to_string(step.cost_terms.size()) + " terms");
  }
  for (std::size_t i = 0; i < constraints_.size(); ++i) {
    if (constraints_[i].sums_all_terms()) {
      costs[static_cast<Eigen::Index>(i)] = step.cost;  // the environment's clipped sum
      continue;
    }
    double sum = 0.0;
    for (std::size_t position : positions_[i]) sum += step.cost_terms[position].value;
    costs[static_cast<Eigen::Index>(i)] = sum;
  }
}

}  // namespace bsg::algos
