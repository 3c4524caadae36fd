#include "algos/lagrange/multiplier.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace bsg::algos {
namespace {

double checked_initial_value(double initial_value) {
  if (!std::isfinite(initial_value) || initial_value < 0.0) {
    throw std::invalid_argument("LagrangeMultiplier: lagrangian_multiplier_init must be finite and >= 0, got " +
                                std::to_string(initial_value));
  }
  return std::max(initial_value, 1e-5);  // the original's max(init, 1e-5)
}

double checked_learning_rate(double learning_rate) {
  if (!std::isfinite(learning_rate) || !(learning_rate > 0.0)) {
    throw std::invalid_argument("LagrangeMultiplier: lambda_lr must be positive, got " +
                                std::to_string(learning_rate));
  }
  return learning_rate;
}

}  // namespace

LagrangeMultiplier::LagrangeMultiplier(double initial_value, LambdaOptimizer optimizer, double learning_rate,
                                       const PidLagrangianOptions& pid)
    : lambda_(checked_initial_value(initial_value)),
      optimizer_(optimizer),
      rule_(make_multiplier_rule(optimizer, checked_learning_rate(learning_rate), lambda_, pid)) {}

LagrangeMultiplier::LagrangeMultiplier(const RunConfig& config)
    : LagrangeMultiplier(config.multiplier.lagrangian_multiplier_init, config.multiplier.lambda_optimizer,
                         config.multiplier.lambda_lr,
                         pid_lagrangian_options(config)) {
  upper_bound_ = config.multiplier.lagrangian_upper_bound;
}

LagrangeMultiplier::LagrangeMultiplier(const LagrangeMultiplier& other)
    : lambda_(other.lambda_),
      optimizer_(other.optimizer_),
      rule_(other.rule_->clone()),
      upper_bound_(other.upper_bound_) {}

LagrangeMultiplier& LagrangeMultiplier::operator=(const LagrangeMultiplier& other) {
  if (this != &other) {
    lambda_ = other.lambda_;
    optimizer_ = other.optimizer_;
    rule_ = other.rule_->clone();
    upper_bound_ = other.upper_bound_;
  }
  return *this;
}

double LagrangeMultiplier::update(double mean_episode_cost, double cost_limit) {
  if (!std::isfinite(mean_episode_cost)) {
    throw std::invalid_argument("LagrangeMultiplier::update: mean_episode_cost (J_C) is not finite: " +
                                std::to_string(mean_episode_cost));
  }
  lambda_ = rule_->step(lambda_, mean_episode_cost, cost_limit);     // lambda >= 0
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
  for (NamedScalar& entry : rule_->diagnostics()) values.push_back(std::move(entry));
  return values;
}

std::vector<NamedScalar> LagrangeMultiplier::state() const {
  std::vector<NamedScalar> saved = {{"lagrange_multiplier", lambda_}};
  for (NamedScalar& entry : rule_->state()) saved.push_back(std::move(entry));
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
  rule_->restore_state(saved.subspan(1));  // validates before any change
  lambda_ = saved[0].value;
}

}  // namespace bsg::algos
