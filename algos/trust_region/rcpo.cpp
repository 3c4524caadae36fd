#include "algos/trust_region/rcpo.h"

namespace bsg::algos {

TrustRegionPlan Rcpo::plan_step(const PolicyUpdateInputs& inputs) {
  // 1. lambda_j first, on this epoch's J_Cj; 2. the penalised advantage (A - sum_j lambda_j A^Cj) / (1 + sum_j lambda_j).
  TrustRegionPlan plan = lagrangian_plan(inputs);
  plan.line_search = false;  // 3. its natural step, whole
  return plan;
}

}  // namespace bsg::algos
