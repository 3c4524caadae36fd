// PDO, primal-dual optimisation (docs/algorithms.md#pdo; the original's algs/pdo):
//   1. lambda update first, on the pooled J_C (Adam by default; moments persist)
//   2. l_old = l_R(theta_old), g = avg grad L_R, b = avg grad L_C
//   3. p = g - lambda b            (no 1/(1+lambda): irrelevant for the step)
//      with m constraints p = g - sum_j lambda_j b_j, one multiplier each
//      (constraint_multipliers.h, docs/algorithms.md#several-constraints)
//   4. x = CG(F, p), q = x^T F x, alpha = sqrt(2 delta / (q + 1e-8)), Delta = alpha x
//   5. line search A on the REWARD-ONLY loss l_R (Q14), budget 15;
//      pdo_line_search: false applies Delta directly
// The original also computes c = (J_C - d) / L but never uses it.
//
// Parameters (RunConfig): target_kl 1e-3, cg_iters 10, cg_damping 0.1,
// backtrack_budget 15, backtrack_decay 0.8, kl_accept_factor 1.5, cost_limit 25,
// lagrangian_multiplier_init 0.001, lambda_optimizer Adam, lambda_lr 0.001,
// pdo_line_search true (lambda_optimizer PID: the pid_* keys, algos/lagrange/pid_lagrangian.h).
#pragma once

#include <Eigen/Core>

#include "algos/trust_region/lagrangian_trust_region.h"
#include "common/run_config.h"

namespace bsg::algos {

// p = g - lambda b
Eigen::VectorXd pdo_search_direction(const Eigen::Ref<const Eigen::VectorXd>& reward_gradient,
                                     const Eigen::Ref<const Eigen::VectorXd>& cost_gradient,
                                     double lagrange_multiplier);

class Pdo final : public LagrangianTrustRegion {
 public:
  explicit Pdo(const RunConfig& config) : LagrangianTrustRegion(config) {}

  std::string_view name() const override { return "pdo"; }

 private:
  // The multipliers' step, then l_R for the line search (or the full step).
  TrustRegionPlan plan_step(const PolicyUpdateInputs& inputs) override;
  // p = g - sum_j lambda_j b_j with this epoch's lambdas; logs |g| and Misc/cost_gradient_norm.
  SearchDirection search_direction(const PolicyUpdateInputs& inputs, const TrustRegionPlan& plan) override;
  std::vector<std::string> own_diagnostic_names() const override;
};

}  // namespace bsg::algos
