#include "envs/saute_env.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace bsg::envs {

double saute_normalized_budget(double limit, double saute_gamma, int max_episode_steps) {
  return limit * (1.0 - std::pow(saute_gamma, max_episode_steps)) / (1.0 - saute_gamma) / max_episode_steps;
}

SauteEnv::SauteEnv(std::unique_ptr<Env> inner, CostBudgets budgets, SauteOptions options)
    : DecoratedEnv(std::move(inner)),
      budgets_(std::move(budgets)),
      options_(options),
      spec_(this->inner().spec()),
      inner_size_(static_cast<std::size_t>(spec_.observation_dim)) {
  const double gamma = options.saute_gamma;
  const int steps = options.max_episode_steps;
  if (budgets_.limits.empty() || !budgets_.step_costs) throw std::invalid_argument("saute: no cost budget");
  if (!(gamma > 0.0 && gamma < 1.0)) {
    throw std::invalid_argument("saute: saute_gamma must be in (0, 1), got " + std::to_string(gamma));
  }
  if (steps < 1) throw std::invalid_argument("saute: max_episode_steps must be >= 1, got " + std::to_string(steps));
  if (!std::isfinite(options.unsafe_reward)) throw std::invalid_argument("saute: unsafe_reward must be finite");
  for (std::size_t i = 0; i < budgets_.limits.size(); ++i) {
    const double limit = budgets_.limits[i];
    if (!(limit > 0.0 && std::isfinite(limit))) {
      throw std::invalid_argument("saute: budget " + std::to_string(i + 1) + " must be positive and finite, got " +
                                  std::to_string(limit));
    }
    normalized_budgets_.push_back(saute_normalized_budget(limit, gamma, steps));
  }
  step_costs_.assign(budget_count(), 0.0);
  start_fractions_.assign(budget_count(), 1.0);
  spec_.observation_dim += static_cast<int>(budget_count());
  observation_.assign(static_cast<std::size_t>(spec_.observation_dim), 1.0);
}

std::span<const double> SauteEnv::augment(std::span<const double> observation) {
  if (observation.size() != inner_size_) {
    throw std::runtime_error("saute: the environment returned an observation of size " +
                             std::to_string(observation.size()) + ", expected " + std::to_string(inner_size_));
  }
  std::copy(observation.begin(), observation.end(), observation_.begin());
  return observation_;
}

void SauteEnv::set_start_fractions(std::span<const double> fractions) {
  if (fractions.size() != budget_count()) {
    throw std::invalid_argument("saute: " + std::to_string(fractions.size()) + " start fractions for " +
                                std::to_string(budget_count()) + " budgets");
  }
  for (std::size_t i = 0; i < fractions.size(); ++i) {
    if (!(fractions[i] > 0.0 && fractions[i] <= 1.0)) {
      throw std::invalid_argument("saute: budget " + std::to_string(i + 1) + "'s start fraction must be in (0, 1], got " +
                                  std::to_string(fractions[i]));
    }
  }
  start_fractions_.assign(fractions.begin(), fractions.end());
}

std::span<const double> SauteEnv::start_episode(std::span<const double> observation) {
  // z_0 = 1 (Saute), or a schedule's fraction of the budget.
  std::copy(start_fractions_.begin(), start_fractions_.end(), observation_.begin() + static_cast<std::ptrdiff_t>(inner_size_));
  return augment(observation);
}

StepResult SauteEnv::step(std::span<const double> action) {
  StepResult result = inner().step(action);
  budgets_.step_costs(result, step_costs_);
  bool spent = false;
  for (std::size_t i = 0; i < budget_count(); ++i) {
    double& z = observation_[inner_size_ + i];
    z = (z - step_costs_[i] / normalized_budgets_[i]) / options_.saute_gamma;  // z_t+1 = (z_t - c_t / d~) / gamma_s
    spent = spent || !(z > 0.0);
  }
  result.observation = augment(result.observation);
  result.learner = LearnerSignal{spent ? options_.unsafe_reward : result.reward, false, spent};
  return result;
}

}  // namespace bsg::envs
