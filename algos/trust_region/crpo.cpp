#include "algos/trust_region/crpo.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace bsg::algos {

int crpo_rectified_constraint(std::span<const ConstraintEstimate> constraints, double tolerance) {
  int rectified = 0;
  double largest_excess = 0.0;
  for (std::size_t i = 0; i < constraints.size(); ++i) {
    const double excess = constraints[i].mean_episode_cost - (constraints[i].limit + tolerance);  // J_Ci - (d_i + eta)
    if (excess > largest_excess) {
      largest_excess = excess;
      rectified = static_cast<int>(i) + 1;
    }
  }
  return rectified;
}

Crpo::Crpo(const RunConfig& config) : TrustRegionAlgorithm(config) {
  if (!std::isfinite(config.trust_region.crpo_tolerance) || config.trust_region.crpo_tolerance < 0.0) {
    throw std::invalid_argument("crpo: crpo_tolerance must be finite and >= 0, got " +
                                std::to_string(config.trust_region.crpo_tolerance));
  }
}

TrustRegionPlan Crpo::plan_step(const PolicyUpdateInputs& inputs) {
  check_mean_episode_cost(inputs, name());
  const std::vector<ConstraintEstimate> constraints = constraint_estimates(inputs, config());
  const int rectified = crpo_rectified_constraint(constraints, config().trust_region.crpo_tolerance);

  TrustRegionPlan plan;  // rectified == 0: the reward surrogate, TRPO's step
  if (rectified > 0) {
    // -l = -L_Cj: the weights (w_R, w_1..w_m) = (0, ..., -1 at j, ...)
    plan.surrogate.reward_weight = 0.0;
    plan.surrogate.cost_weights.assign(constraints.size(), 0.0);
    plan.surrogate.cost_weights[static_cast<std::size_t>(rectified - 1)] = -1.0;
  }
  plan.own_columns.push_back({"crpo_case", static_cast<double>(rectified)});
  return plan;
}

}  // namespace bsg::algos
