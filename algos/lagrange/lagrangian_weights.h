// The weights a Lagrangian method puts on the reward and cost surrogates,
// shared by TRPO-L (algos/trust_region/lag_trpo.h) and PPO-Lag
// (algos/first_order/ppo.h): -l_L = w_R L_R + sum_j w_j L_Cj with
// l_L = (-L_R + sum_j lambda_j L_Cj) / (1 + sum_j lambda_j)
// (docs/algorithms.md#trpo-l).
#pragma once

#include <span>
#include <vector>

namespace bsg::algos {

// Weights (w_R, w_C) with -l_L = w_R L_R + w_C L_C: (1/(1+lambda), -lambda/(1+lambda)).
struct SurrogateWeights {
  double reward = 1.0;
  double cost = 0.0;
};
SurrogateWeights lagrangian_surrogate_weights(double lagrange_multiplier);

// With m multipliers: w_R = 1 / (1 + sum lambda), w_j = -lambda_j / (1 + sum lambda).
struct ConstraintSurrogateWeights {
  double reward = 1.0;
  std::vector<double> costs;
};
ConstraintSurrogateWeights lagrangian_surrogate_weights(std::span<const double> lagrange_multipliers);

}  // namespace bsg::algos
