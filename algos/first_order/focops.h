// FOCOPS, First Order Constrained Optimization in Policy Space
// (docs/algorithms.md#focops; Zhang, Vuong and Ross 2020, NeurIPS, Algorithm 1):
//   0. every nu_j >= 0 updates first on its J_Cj (constraint_multipliers.h; the
//      paper's nu <- proj(nu - alpha_nu (d - J_C)) is the SGD rule), and
//      A_hat_i = A_i - sum_j nu_j A^Cj_i          (eq. 8 with one term per constraint)
//   1. minibatch passes (first_order_update.h) on the paper's loss (eq. 12)
//      l_i = (KL_i - rho_i A_hat_i / lambda) 1[KL_i <= eta]
//      with KL_i = KL(pi_theta || pi_theta_k)[s_i] to the policy of the update's
//      start; the indicator is held constant (it has no gradient), so samples
//      that have moved further than eta leave the loss.
// With one constraint this is the paper's algorithm; with m, the optimal
// policy of the paper's eq. 8 weighs each cost advantage by its own nu_j.
//
// Parameters (RunConfig): focops_lam 1.5, focops_eta 0.02 (the paper's), the
// first-order keys, and the multiplier keys (lambda_optimizer, lambda_lr, ...).
#pragma once

#include "algos/first_order/first_order_algorithm.h"
#include "algos/first_order/first_order_update.h"
#include "common/run_config.h"

namespace bsg::algos {

// l_i = (KL_i - rho_i A_i / temperature) 1[KL_i <= kl_bound] for A_i = advantages[i]
// (which must outlive the function).
SampleLossFunction focops_loss(const Eigen::VectorXd& advantages, double temperature, double kl_bound);

class Focops final : public FirstOrderAlgorithm {
 public:
  explicit Focops(const RunConfig& config);

  std::string_view name() const override { return "focops"; }
  PolicyUpdateResult update(const PolicyUpdateInputs& inputs) override;
};

}  // namespace bsg::algos
