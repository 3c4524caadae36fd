#include "algos/lagrange/adam_multiplier_rule.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace bsg::algos {
namespace {

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
  return {{"lagrange_multiplier_adam_m", adam_.first_moment()[0]},
          {"lagrange_multiplier_adam_v", adam_.second_moment()[0]},
          {"lagrange_multiplier_adam_t", static_cast<double>(adam_.step_count())}};
}

void AdamMultiplierRule::restore_state(std::span<const NamedScalar> saved) {
  const double step_count = saved[2].value;
  if (!(step_count >= 0.0) || step_count != std::floor(step_count)) {
    throw std::invalid_argument("LagrangeMultiplier::restore_state: lagrange_multiplier_adam_t must be a "
                                "non-negative integer, got " + std::to_string(step_count));
  }
  adam_.set_state(Eigen::VectorXd::Constant(1, saved[0].value), Eigen::VectorXd::Constant(1, saved[1].value),
                  static_cast<long long>(step_count));
}

}  // namespace bsg::algos
