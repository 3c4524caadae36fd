// TRPO-L, Lagrangian TRPO (docs/algorithms.md#trpo-l; the original's algs/lag-trpo):
//   1. lambda update first, on the pooled J_C (SGD by default; see multiplier.h)
//   2. l_L(theta) = (-L_R(theta) + lambda L_C(theta)) / (1 + lambda), so
//      g_L = -avg grad l_L = (g - lambda b) / (1 + lambda)
//   3. TRPO steps 2-4 with g_L in place of g; line search A on l_L
// The (1 + lambda) does not change the (renormalised) step, only the logged
// losses and the interplay with CG's 1e-6. The reward itself is not modified.
// With m constraints (docs/algorithms.md#several-constraints) each has its own multiplier
// lambda_j (constraint_multipliers.h) and
//   l_L = (-L_R + sum_j lambda_j L_Cj) / (1 + sum_j lambda_j),
// the combined advantage A_i - sum_j lambda_j A^Cj_i over 1 + sum_j lambda_j.
//
// Parameters (RunConfig): those of TRPO plus cost_limit 25,
// lagrangian_multiplier_init 0.001, lambda_optimizer SGD, lambda_lr 0.05 (or
// lambda_optimizer PID and the pid_* keys: algos/lagrange/pid_lagrangian.h).
#pragma once

#include "algos/trust_region/lagrangian_trust_region.h"
#include "common/run_config.h"

namespace bsg::algos {

class LagTrpo final : public LagrangianTrustRegion {
 public:
  explicit LagTrpo(const RunConfig& config) : LagrangianTrustRegion(config) {}

  std::string_view name() const override { return "lag-trpo"; }

 private:
  TrustRegionPlan plan_step(const PolicyUpdateInputs& inputs) override;
};

}  // namespace bsg::algos
