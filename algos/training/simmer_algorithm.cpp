#include "algos/training/simmer_algorithm.h"

#include <stdexcept>
#include <string>
#include <utility>

#include "algos/core/constraint_costs.h"
#include "envs/saute_env.h"

namespace bsg::algos {
namespace {

// J~ or d~: an episode cost in Saute's normalised units (envs/saute_env.h).
double normalized(const RunConfig& config, double episode_cost) {
  return envs::saute_normalized_budget(episode_cost, config.budget.saute_gamma, config.max_ep_len);
}

std::string controller_prefix(std::size_t i) { return "simmer_" + std::to_string(i + 1) + "_"; }

}  // namespace

SimmerAlgorithm::SimmerAlgorithm(const RunConfig& config, std::unique_ptr<OnPolicyAlgorithm> base)
    : OnPolicyAlgorithm(config), base_(std::move(base)) {
  if (!schedules_saute_budgets(config.alg)) {
    throw std::invalid_argument("SimmerAlgorithm: alg must be ppo-simmer or trpo-simmer, got " +
                                std::string(to_string(config.alg)));
  }
  if (base_ == nullptr) throw std::invalid_argument("SimmerAlgorithm: no base algorithm");
  const BudgetKeys& keys = config.budget;
  for (int i = 0; i < constraint_count(config); ++i) {
    const double limit = constraint_limit(config, i);
    normalized_limits_.push_back(normalized(config, limit));
    controllers_.emplace_back(SimmerControllerOptions{keys.simmer_kp, keys.simmer_ki, keys.simmer_kd,
                                                      keys.simmer_polyak, normalized_limits_.back(),
                                                      normalized(config, keys.simmer_initial_budget_fraction * limit)});
  }
}

PolicyUpdateResult SimmerAlgorithm::update(const PolicyUpdateInputs& inputs) {
  const std::vector<double> collected_with = budgets();
  const std::vector<ConstraintEstimate> estimates = constraint_estimates(inputs, config());
  if (estimates.size() != controllers_.size()) {
    throw std::invalid_argument("SimmerAlgorithm: " + std::to_string(estimates.size()) + " constraints for " +
                                std::to_string(controllers_.size()) + " budgets");
  }
  for (std::size_t i = 0; i < controllers_.size(); ++i) {
    controllers_[i].step(normalized(config(), estimates[i].mean_episode_cost));  // b~_k+1 from J~_k
  }
  PolicyUpdateResult result = base_->update(inputs);
  const std::vector<std::string> names = diagnostic_names();
  for (std::size_t i = 0; i < collected_with.size(); ++i) {
    result.diagnostics.push_back({names[names.size() - collected_with.size() + i], collected_with[i]});
  }
  return result;
}

std::vector<std::string> SimmerAlgorithm::diagnostic_names() const {
  std::vector<std::string> names = base_->diagnostic_names();
  if (controllers_.size() == 1) {
    names.emplace_back("Simmer/Budget");
  } else {
    for (std::size_t i = 0; i < controllers_.size(); ++i) names.push_back("Simmer/Budget_" + std::to_string(i + 1));
  }
  return names;
}

std::vector<NamedScalar> SimmerAlgorithm::state() const {
  std::vector<NamedScalar> state = base_->state();
  for (std::size_t i = 0; i < controllers_.size(); ++i) {
    const std::vector<NamedScalar> own = controllers_[i].state(controller_prefix(i));
    state.insert(state.end(), own.begin(), own.end());
  }
  return state;
}

void SimmerAlgorithm::restore_state(std::span<const NamedScalar> saved) {
  const std::size_t own = controllers_.size() * SimmerBudgetController::state_size();
  if (saved.size() < own) {
    throw std::invalid_argument(std::string(name()) + ": restore_state expects the state of " +
                                std::to_string(controllers_.size()) + " Simmer controllers, got " +
                                std::to_string(saved.size()) + " values");
  }
  const std::size_t base_size = saved.size() - own;
  base_->restore_state(saved.first(base_size));
  for (std::size_t i = 0; i < controllers_.size(); ++i) {
    controllers_[i].restore_state(saved.subspan(base_size + i * SimmerBudgetController::state_size(),
                                                SimmerBudgetController::state_size()),
                                  controller_prefix(i));
  }
}

std::vector<double> SimmerAlgorithm::start_fractions() const {
  std::vector<double> fractions;
  for (std::size_t i = 0; i < controllers_.size(); ++i) fractions.push_back(controllers_[i].budget() / normalized_limits_[i]);
  return fractions;
}

std::vector<double> SimmerAlgorithm::budgets() const {
  std::vector<double> budgets;
  const std::vector<double> fractions = start_fractions();
  for (std::size_t i = 0; i < fractions.size(); ++i) budgets.push_back(fractions[i] * constraint_limit(config(), static_cast<int>(i)));
  return budgets;
}

}  // namespace bsg::algos
