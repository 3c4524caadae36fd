#include "algos/trust_region/lag_trpo.h"

namespace bsg::algos {

TrustRegionPlan LagTrpo::plan_step(const PolicyUpdateInputs& inputs) {
  // 1. lambda_j updates (SGD by default: lambda <- max(0, lambda + alpha_lambda (J_Cj - d_j))), before the policy step.
  // 2. -l_L = (L_R - sum_j lambda_j L_Cj) / (1 + sum_j lambda_j): its gradient g_L and line search A on l_L.
  return lagrangian_plan(inputs);
}

}  // namespace bsg::algos
