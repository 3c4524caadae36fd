#include "algos/lagrange/lagrangian_weights.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace bsg::algos {

SurrogateWeights lagrangian_surrogate_weights(double lagrange_multiplier) {
  const ConstraintSurrogateWeights weights =
      lagrangian_surrogate_weights(std::span<const double>(&lagrange_multiplier, 1));
  return {weights.reward, weights.costs.front()};
}

ConstraintSurrogateWeights lagrangian_surrogate_weights(std::span<const double> lagrange_multipliers) {
  double normaliser = 1.0;  // 1 + sum_j lambda_j
  for (double lambda : lagrange_multipliers) {
    if (!std::isfinite(lambda) || lambda < 0.0) {
      throw std::invalid_argument("lagrangian_surrogate_weights: lagrange_multiplier must be finite and >= 0, got " +
                                  std::to_string(lambda));
    }
    normaliser += lambda;
  }
  ConstraintSurrogateWeights weights;
  weights.reward = 1.0 / normaliser;
  for (double lambda : lagrange_multipliers) weights.costs.push_back(-lambda / normaliser);
  return weights;
}

}  // namespace bsg::algos
