// PPO, the clipped surrogate (docs/algorithms.md#ppo; Schulman, Wolski, Dhariwal,
// Radford and Klimov 2017, eq. 7), and PPO-Lag, its Lagrangian form
// (docs/algorithms.md#ppo-lag; Ray, Achiam and Amodei 2019, Safety Gym's baseline;
// with lambda_optimizer PID it is CPPO-PID, Stooke, Achiam and Abbeel 2020):
//   0. PPO-Lag only: every multiplier lambda_j updates first on its J_Cj
//      (constraint_multipliers.h), and the advantage becomes
//      A_hat_i = (A_i - sum_j lambda_j A^Cj_i) / (1 + sum_j lambda_j)   (OmniSafe's PPOLag)
//      (PPO: A_hat = A)
//   1. minibatch passes (first_order_update.h) on
//      l_i = -min(rho_i A_hat_i, clip(rho_i, 1 - eps, 1 + eps) A_hat_i)
//      whose derivative is -A_hat_i where the unclipped term is the smaller
//      one and 0 where the clip holds it (rho_i > 1 + eps with A_hat_i > 0,
//      rho_i < 1 - eps with A_hat_i < 0).
// PPO trains no cost value net (use_cost_value_function: false).
//
// Parameters (RunConfig): clip 0.2 and the first-order keys; PPO-Lag also
// cost_limit, lagrangian_multiplier_init 0.001, lambda_optimizer Adam,
// lambda_lr 0.035 (OmniSafe's defaults) or the pid_* keys.
#pragma once

#include "algos/first_order/first_order_algorithm.h"
#include "algos/first_order/first_order_update.h"
#include "common/run_config.h"

namespace bsg::algos {

// l_i = -min(rho_i A_i, clip(rho_i, 1 - clip, 1 + clip) A_i) for A_i = advantages[i]
// (which must outlive the function); KL_i plays no part.
SampleLossFunction clipped_surrogate_loss(const Eigen::VectorXd& advantages, double clip);

class Ppo final : public FirstOrderAlgorithm {
 public:
  // alg ppo or ppo-lag.
  explicit Ppo(const RunConfig& config);

  // ppo, ppo-lag, or a budget method's spelling (ppo-saute, ...): its checkpoint's name.
  std::string_view name() const override { return to_string(config().alg); }
  PolicyUpdateResult update(const PolicyUpdateInputs& inputs) override;
};

}  // namespace bsg::algos
