#include "algos/lagrange/adam_multiplier_rule.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <string_view>

#include "algos/core/adam_state.h"

namespace bsg::algos {
namespace {

// The rule's state entries (algos/core/adam_state.h): lagrange_multiplier_adam_m, _v, _t.
constexpr std::string_view kAdamPrefix = "lagrange_multiplier_adam_";

AdamOptions lambda_adam_options(double learning_rate) {
  AdamOptions options;
  options.learning_rate = learning_rate;  // beta (0.9, 0.999), eps 1e-8 as PyTorch's defaults
  return options;
}

}  // namespace

AdamMultiplierRule::AdamMultiplierRule(double learning_rate) : adam_(1, lambda_adam_options(learning_rate)) {}

double AdamMultiplierRule::step(double lambda, double mean_episode_cost, double cost_limit) {
  const double violation = mean_episode_cost - cost_limit;  // J_C - d
  Eigen::VectorXd parameter = Eigen::VectorXd::Constant(1, lambda);
  adam_.step(parameter, Eigen::VectorXd::Constant(1, -violation));  // gradient -(J_C - d)
  return std::max(parameter[0], 0.0);  // projection onto lambda >= 0, after the step
}

std::vector<NamedScalar> AdamMultiplierRule::state() const {
  return adam_state_entries(adam_, kAdamPrefix, AdamEntryLayout::moments_then_step);
}

void AdamMultiplierRule::restore_state(std::span<const NamedScalar> saved) {
  restore_adam_state_entries(adam_, saved, kAdamPrefix, AdamEntryLayout::moments_then_step);
}

}  // namespace bsg::algos
