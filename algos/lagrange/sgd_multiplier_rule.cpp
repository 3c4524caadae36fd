#include "algos/lagrange/sgd_multiplier_rule.h"

#include <algorithm>

namespace bsg::algos {

double SgdMultiplierRule::step(double lambda, double mean_episode_cost, double cost_limit) {
  const double violation = mean_episode_cost - cost_limit;  // J_C - d
  lambda = lambda + learning_rate_ * violation;              // lambda - lr * d/dlambda[-lambda (J_C - d)]
  return std::max(lambda, 0.0);                              // projection onto lambda >= 0, after the step
}

}  // namespace bsg::algos
