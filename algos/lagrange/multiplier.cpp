#include "algos/lagrange/multiplier.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "algos/core/adam_state.h"

namespace bsg::algos {
namespace {

// The Adam rule's state entries (adam_state.h): lagrange_multiplier_adam_m, _v, _t.
constexpr std::string_view kAdamPrefix = "lagrange_multiplier_adam_";

AdamOptions lambda_adam_options(double learning_rate) {
  AdamOptions options;
  options.learning_rate = learning_rate;  // beta (0.9, 0.999), eps 1e-8 as PyTorch's defaults
  return options;
}

double checked_initial_value(double initial_value) {
  if (!std::isfinite(initial_value) || initial_value < 0.0) {
    throw std::invalid_argument("LagrangeMultiplier: lagrangian_multiplier_init must be finite and >= 0, got " +
                                std::to_string(initial_value));
  }
  return std::max(initial_value, 1e-5);  // the original's max(init, 1e-5)
}

}  // namespace

LagrangeMultiplier::LagrangeMultiplier(double initial_value, LambdaOptimizer optimizer, double learning_rate,
                                       const PidLagrangianOptions& pid)
    : lambda_(checked_initial_value(initial_value)),
      optimizer_(optimizer),
      learning_rate_(learning_rate),
      adam_(1, lambda_adam_options(learning_rate)),
      pid_(lambda_, pid) {
  if (!std::isfinite(learning_rate) || !(learning_rate > 0.0)) {
    throw std::invalid_argument("LagrangeMultiplier: lambda_lr must be positive, got " +
                                std::to_string(learning_rate));
  }
}

LagrangeMultiplier::LagrangeMultiplier(const RunConfig& config)
    : LagrangeMultiplier(config.lagrangian_multiplier_init, config.lambda_optimizer, config.lambda_lr,
                         pid_lagrangian_options(config)) {
  upper_bound_ = config.lagrangian_upper_bound;
}

double LagrangeMultiplier::update(double mean_episode_cost, double cost_limit) {
  if (!std::isfinite(mean_episode_cost)) {
    throw std::invalid_argument("LagrangeMultiplier::update: mean_episode_cost (J_C) is not finite: " +
                                std::to_string(mean_episode_cost));
  }
  if (optimizer_ == LambdaOptimizer::pid) {
    lambda_ = pid_.update(mean_episode_cost, cost_limit).lambda;  // max(0, P + I + D), at most lambda_max
    if (upper_bound_ > 0.0) lambda_ = std::min(lambda_, upper_bound_);
    return lambda_;
  }
  const double violation = mean_episode_cost - cost_limit;  // J_C - d
  if (optimizer_ == LambdaOptimizer::sgd) {
    lambda_ = lambda_ + learning_rate_ * violation;  // lambda - lr * d/dlambda[-lambda (J_C - d)]
  } else {
    Eigen::VectorXd parameter = Eigen::VectorXd::Constant(1, lambda_);
    adam_.step(parameter, Eigen::VectorXd::Constant(1, -violation));  // gradient -(J_C - d)
    lambda_ = parameter[0];
  }
  lambda_ = std::max(lambda_, 0.0);  // projection onto lambda >= 0, after the step
  if (upper_bound_ > 0.0) lambda_ = std::min(lambda_, upper_bound_);  // FOCOPS: onto [0, nu_max]
  return lambda_;
}

std::vector<std::string> LagrangeMultiplier::diagnostic_names() const {
  std::vector<std::string> names;
  for (NamedScalar& entry : diagnostics()) names.push_back(std::move(entry.name));
  return names;
}

std::vector<NamedScalar> LagrangeMultiplier::diagnostics() const {
  std::vector<NamedScalar> values = {{"LagrangeMultiplier", lambda_}};
  if (optimizer_ == LambdaOptimizer::pid) {
    const PidTerms& terms = pid_.last_terms();
    values.insert(values.end(),
                  {{"PID/P", terms.proportional}, {"PID/I", terms.integral}, {"PID/D", terms.derivative}});
  }
  return values;
}

std::vector<NamedScalar> LagrangeMultiplier::state() const {
  std::vector<NamedScalar> saved = {{"lagrange_multiplier", lambda_}};
  if (optimizer_ == LambdaOptimizer::pid) {
    for (NamedScalar& entry : pid_.state()) saved.push_back(std::move(entry));
  }
  if (optimizer_ == LambdaOptimizer::adam) {
    for (NamedScalar& entry : adam_state_entries(adam_, kAdamPrefix, AdamEntryLayout::moments_then_step)) {
      saved.push_back(std::move(entry));
    }
  }
  return saved;
}

void LagrangeMultiplier::restore_state(std::span<const NamedScalar> saved) {
  const std::vector<NamedScalar> expected = state();
  if (saved.size() != expected.size()) {
    throw std::invalid_argument("LagrangeMultiplier::restore_state: expected " + std::to_string(expected.size()) +
                                " values for the " + std::string(to_string(optimizer_)) +
                                " multiplier, got " + std::to_string(saved.size()));
  }
  for (std::size_t i = 0; i < saved.size(); ++i) {
    if (saved[i].name != expected[i].name) {
      throw std::invalid_argument("LagrangeMultiplier::restore_state: entry " + std::to_string(i) + " is '" +
                                  saved[i].name + "', expected '" + expected[i].name + "'");
    }
  }
  if (!std::isfinite(saved[0].value) || saved[0].value < 0.0) {
    throw std::invalid_argument("LagrangeMultiplier::restore_state: lagrange_multiplier must be finite and >= 0, got " +
                                std::to_string(saved[0].value));
  }
  if (optimizer_ == LambdaOptimizer::pid) pid_.restore_state(saved.subspan(1));  // validates before any change
  lambda_ = saved[0].value;
  if (optimizer_ == LambdaOptimizer::adam) {
    restore_adam_state_entries(adam_, saved.subspan(1), kAdamPrefix, AdamEntryLayout::moments_then_step);
  }
}

}  // namespace bsg::algos
