// TRPO (docs/algorithms.md#trpo; Schulman et al. 2015, as the original's algs/trpo/trpo.py
// on top of NPG): the trust-region base (trust_region_algorithm.h) on the reward alone,
//   1. l_old = l_R(theta_old), g = avg grad L_R
//   2. x = CG(F, g), q = x^T F x, alpha = sqrt(2 delta / (q + 1e-8)), Delta = alpha x
//   3. line search A on l_R (budget 15, decay 0.8, KL <= 1.5 delta)
//   4. theta <- theta_old + final step
// The cost value net is not trained (use_cost_value_function: false).
//
// Parameters (RunConfig): target_kl 0.01, cg_iters 10, cg_damping 0.1,
// fvp_subsample 4, backtrack_budget 15, backtrack_decay 0.8, kl_accept_factor 1.5.
#pragma once

#include "algos/trust_region/trust_region_algorithm.h"
#include "common/run_config.h"

namespace bsg::algos {

class Trpo final : public TrustRegionAlgorithm {
 public:
  explicit Trpo(const RunConfig& config) : TrustRegionAlgorithm(config) {}

  // trpo, or a budget method's spelling (trpo-saute, ...): its checkpoint's name.
  std::string_view name() const override { return to_string(config().alg); }

 private:
  TrustRegionPlan plan_step(const PolicyUpdateInputs& /*inputs*/) override { return {}; }  // l_R, line search
};

}  // namespace bsg::algos
