#include "algos/trust_region/lag_trpo.h"

#include "algos/lagrange/lagrangian_weights.h"

namespace bsg::algos {

TrustRegionPlan LagTrpo::plan_step(const PolicyUpdateInputs& inputs) {
  // 1. lambda_j updates (SGD by default: lambda <- max(0, lambda + alpha_lambda (J_Cj - d_j))), before the policy step.
  ConstraintSurrogateWeights weights = lagrangian_surrogate_weights(update_multipliers(inputs));
  // 2. -l_L = (L_R - sum_j lambda_j L_Cj) / (1 + sum_j lambda_j): its gradient g_L and line search A on l_L.
  TrustRegionPlan plan;
  plan.surrogate.reward_weight = weights.reward;
  plan.surrogate.cost_weights = std::move(weights.costs);
  return plan;
}

}  // namespace bsg::algos
