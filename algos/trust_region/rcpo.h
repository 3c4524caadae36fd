// RCPO, reward-constrained policy optimisation (docs/algorithms.md#rcpo; Tessler, Mankowitz
// and Mannor, ICLR 2019), as OmniSafe's RCPO: the natural policy gradient (its NaturalPG base)
// on the penalised reward r - sum_j lambda_j c_j, a variant of the Lagrangian trust-region base:
//   1. every lambda_j updates first on its J_Cj (Adam by default, as OmniSafe's Lagrange)
//   2. -l = (L_R - sum_j lambda_j L_Cj) / (1 + sum_j lambda_j): the advantage of the
//      penalised reward, A_i - sum_j lambda_j A^Cj_i (GAE is linear in the reward and the
//      value, so this is the GAE of r - sum_j lambda_j c_j with V - sum_j lambda_j V_Cj),
//      over 1 + sum_j lambda_j as OmniSafe's
//   3. x = CG(F, g_l), alpha = sqrt(2 delta / (x^T F x + 1e-8)), theta = theta_old + alpha x,
//      without a line search (what sets it apart from TRPO-L)
// The paper's actor-critic learns a critic of the penalised reward itself; OmniSafe, and this
// file, fold the penalty into the advantage of the two critics V and V_Cj instead.
//
// Parameters (RunConfig): target_kl, cg_iters, cg_damping, fvp_subsample (no backtrack_*
// or kl_accept_factor), cost_limit or constraints, lagrangian_multiplier_init 0.001,
// lambda_optimizer Adam, lambda_lr 0.035 (OmniSafe's RCPO.yaml) or the pid_* keys.
#pragma once

#include "algos/trust_region/lagrangian_trust_region.h"
#include "common/run_config.h"

namespace bsg::algos {

class Rcpo final : public LagrangianTrustRegion {
 public:
  explicit Rcpo(const RunConfig& config) : LagrangianTrustRegion(config) {}

  std::string_view name() const override { return "rcpo"; }

 private:
  TrustRegionPlan plan_step(const PolicyUpdateInputs& inputs) override;
};

}  // namespace bsg::algos
