#include "algos/training/simmer_budget_controller.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace bsg::algos {
namespace {

std::string number(double value) { return std::to_string(value); }

}  // namespace

SimmerBudgetController::SimmerBudgetController(const SimmerControllerOptions& options)
    : options_(options), budget_(options.initial_budget) {
  const auto gain = [](double value, const char* name) {
    if (!(value >= 0.0 && std::isfinite(value))) {
      throw std::invalid_argument(std::string("Simmer controller: ") + name + " must be >= 0 and finite, got " +
                                  number(value));
    }
  };
  gain(options.kp, "kp");
  gain(options.ki, "ki");
  gain(options.kd, "kd");
  if (!(options.polyak >= 0.0 && options.polyak < 1.0)) {
    throw std::invalid_argument("Simmer controller: polyak must be in [0, 1), got " + number(options.polyak));
  }
  if (!(options.budget_ceiling >= kBudgetFloor && std::isfinite(options.budget_ceiling))) {
    throw std::invalid_argument("Simmer controller: the budget ceiling must be finite and at least 1e-6, got " +
                                number(options.budget_ceiling));
  }
  if (!(options.initial_budget > 0.0 && options.initial_budget <= options.budget_ceiling)) {
    throw std::invalid_argument("Simmer controller: the first budget must be in (0, " +
                                number(options.budget_ceiling) + "], got " + number(options.initial_budget));
  }
}

double SimmerBudgetController::step(double mean_episode_cost) {
  if (!std::isfinite(mean_episode_cost)) {
    throw std::invalid_argument("Simmer controller: the mean episode cost is not finite (" + number(mean_episode_cost) +
                                ")");
  }
  const double error = options_.polyak * error_ + (1.0 - options_.polyak) * (budget_ - mean_episode_cost);  // e_k
  errors_.push_back(error);
  if (errors_.size() > kIntegralWindow) errors_.pop_front();
  double error_sum = 0.0;
  for (double e : errors_) error_sum += e;  // oldest first, as Python's sum over the deque
  const double raw_step =
      options_.kp * error + options_.ki * error_sum + options_.kd * (step_taken_ - raw_step_);  // u_k
  const double bounded_step = std::clamp(raw_step, -kStepBound, kStepBound);
  const double next_budget = std::clamp(budget_ + bounded_step, kBudgetFloor, options_.budget_ceiling);
  step_taken_ = next_budget - budget_;  // s_k, after both clips
  raw_step_ = raw_step;
  error_ = error;
  budget_ = next_budget;
  return budget_;
}

std::vector<NamedScalar> SimmerBudgetController::state(const std::string& prefix) const {
  std::vector<NamedScalar> state = {{prefix + "budget", budget_},
                                    {prefix + "error", error_},
                                    {prefix + "step_taken", step_taken_},
                                    {prefix + "raw_step", raw_step_},
                                    {prefix + "errors_kept", static_cast<double>(errors_.size())}};
  for (std::size_t i = 0; i < kIntegralWindow; ++i) {
    state.push_back({prefix + "errors_" + std::to_string(i), i < errors_.size() ? errors_[i] : 0.0});
  }
  return state;
}

void SimmerBudgetController::restore_state(std::span<const NamedScalar> saved, const std::string& prefix) {
  const std::vector<NamedScalar> expected = state(prefix);
  if (saved.size() != expected.size()) {
    throw std::invalid_argument("Simmer controller: " + std::to_string(saved.size()) + " saved values, expected " +
                                std::to_string(expected.size()));
  }
  for (std::size_t i = 0; i < saved.size(); ++i) {
    if (saved[i].name != expected[i].name) {
      throw std::invalid_argument("Simmer controller: saved value " + std::to_string(i + 1) + " is '" + saved[i].name +
                                  "', expected '" + expected[i].name + "'");
    }
  }
  const double kept = saved[4].value;
  if (!(kept >= 0.0 && kept <= static_cast<double>(kIntegralWindow) && kept == std::floor(kept))) {
    throw std::invalid_argument("Simmer controller: " + number(kept) + " errors kept, at most " +
                                std::to_string(kIntegralWindow));
  }
  if (!(saved[0].value >= kBudgetFloor && saved[0].value <= options_.budget_ceiling)) {
    throw std::invalid_argument("Simmer controller: the saved budget " + number(saved[0].value) + " is outside [" +
                                number(kBudgetFloor) + ", " + number(options_.budget_ceiling) + "]");
  }
  budget_ = saved[0].value;
  error_ = saved[1].value;
  step_taken_ = saved[2].value;
  raw_step_ = saved[3].value;
  errors_.clear();
  for (std::size_t i = 0; i < static_cast<std::size_t>(kept); ++i) errors_.push_back(saved[5 + i].value);
}

}  // namespace bsg::algos
