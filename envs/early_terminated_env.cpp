#include "envs/early_terminated_env.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace bsg::envs {

EarlyTerminatedEnv::EarlyTerminatedEnv(std::unique_ptr<Env> inner, CostBudgets budgets)
    : DecoratedEnv(std::move(inner)), budgets_(std::move(budgets)) {
  if (budgets_.limits.empty() || !budgets_.step_costs) throw std::invalid_argument("early termination: no cost budget");
  for (std::size_t i = 0; i < budgets_.limits.size(); ++i) {
    const double limit = budgets_.limits[i];
    if (!(limit >= 0.0 && std::isfinite(limit))) {
      throw std::invalid_argument("early termination: budget " + std::to_string(i + 1) +
                                  " must be >= 0 and finite, got " + std::to_string(limit));
    }
  }
  step_costs_.assign(budgets_.limits.size(), 0.0);
  episode_costs_.assign(budgets_.limits.size(), 0.0);
}

std::span<const double> EarlyTerminatedEnv::start_episode(std::span<const double> observation) {
  std::fill(episode_costs_.begin(), episode_costs_.end(), 0.0);
  return observation;
}

StepResult EarlyTerminatedEnv::step(std::span<const double> action) {
  StepResult result = inner().step(action);
  budgets_.step_costs(result, step_costs_);
  bool cut = false;
  for (std::size_t i = 0; i < episode_costs_.size(); ++i) {
    episode_costs_[i] += step_costs_[i];
    cut = cut || episode_costs_[i] > budgets_.limits[i];
  }
  result.learner = LearnerSignal{cut ? 0.0 : result.reward, cut, cut};
  return result;
}

}  // namespace bsg::envs
