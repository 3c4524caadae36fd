#include "algos/trust_region/rcpo.h"

#include <utility>

#include "algos/lagrange/lagrangian_weights.h"

namespace bsg::algos {

TrustRegionPlan Rcpo::plan_step(const PolicyUpdateInputs& inputs) {
  // 1. lambda_j first, on this epoch's J_Cj.
  ConstraintSurrogateWeights weights = lagrangian_surrogate_weights(update_multipliers(inputs));
  // 2.-3. The penalised advantage (A - sum_j lambda_j A^Cj) / (1 + sum_j lambda_j), its full natural step.
  TrustRegionPlan plan;
  plan.surrogate.reward_weight = weights.reward;
  plan.surrogate.cost_weights = std::move(weights.costs);
  plan.line_search = false;
  return plan;
}

}  // namespace bsg::algos
