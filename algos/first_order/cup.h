// CUP, Constrained Update Projection (docs/algorithms.md#cup; Yang, Ji, Dai,
// Zhang, Zhou, Li, Yang and Pan 2022, Algorithm 1 as OmniSafe implements it):
//   0. every nu_j >= 0 updates first on its J_Cj (constraint_multipliers.h)
//   1. performance step: PPO's clipped-surrogate passes on the reward
//      advantage A (ppo.h), giving pi_{k+1/2}
//   2. projection step: passes from pi_{k+1/2} on
//      l_i = KL_i + c rho_i sum_j nu_j A^Cj_i,   c = (1 - gamma lam_c) / (1 - gamma)
//      with KL_i = KL(pi_theta || pi_{k+1/2})[s_i] (the KL early stop also
//      measured to pi_{k+1/2}) and rho_i the ratio to the policy that collected
//      the batch: the policy nearest to pi_{k+1/2} whose cost surrogate is low.
// With one constraint this is CUP's projection with the Lagrangian relaxation
// of its cost constraint; with m each cost advantage has its own nu_j.
//
// Parameters (RunConfig): clip (step 1), gamma and lam_c (c), the first-order
// keys (both steps share Adam and the pass options) and the multiplier keys.
#pragma once

#include "algos/first_order/first_order_algorithm.h"
#include "algos/first_order/first_order_update.h"
#include "common/run_config.h"

namespace bsg::algos {

// l_i = KL_i + rho_i cost_advantages[i] for the already weighted c sum_j nu_j A^Cj_i
// (which must outlive the function).
SampleLossFunction cup_projection_loss(const Eigen::VectorXd& weighted_cost_advantages);

class Cup final : public FirstOrderAlgorithm {
 public:
  explicit Cup(const RunConfig& config);

  std::string_view name() const override { return "cup"; }
  PolicyUpdateResult update(const PolicyUpdateInputs& inputs) override;
};

}  // namespace bsg::algos
