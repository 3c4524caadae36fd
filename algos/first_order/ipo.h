// IPO, interior-point policy optimisation (docs/algorithms.md#ipo; Liu, Ding and Liu, AAAI
// 2020), as OmniSafe's IPO: PPO's clipped surrogate plus the log barrier
// phi(J_Cj) = (1/t) log(d_j - J_Cj) of every constraint, whose gradient is the cost surrogate's
// times the penalty p_j = kappa / (d_j - J_Cj), kappa = 1/t. Each epoch:
//   0. p_j = kappa / (d_j - J_Cj + 1e-8), or p_max when that is negative (J_Cj > d_j, outside
//      the barrier's domain) or above p_max (OmniSafe's clamp of the barrier's pole)
//   1. A_hat_i = (A_i - sum_j p_j A^Cj_i) / (1 + sum_j p_j) (OmniSafe's normalisation)
//   2. PPO's minibatch passes on A_hat (ppo.h)
// With m constraints each has its own barrier, so each its own p_j; with one it is the paper's.
// The penalties are a closed form of this epoch's J_Cj: IPO keeps no state but the policy's Adam.
//
// Columns: ipo_penalty (constraint_<j>_ipo_penalty with m >= 2), p_j of this epoch.
// Parameters (RunConfig): clip, the first-order keys, ipo_kappa 0.01, ipo_penalty_max 1
// (OmniSafe's IPO.yaml), cost_limit or constraints.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "algos/first_order/first_order_algorithm.h"
#include "common/run_config.h"

namespace bsg::algos {

// p_j of each constraint: kappa / (d_j - J_Cj + 1e-8), or penalty_max if that is < 0 or > penalty_max.
std::vector<double> ipo_penalties(std::span<const ConstraintEstimate> constraints, double kappa, double penalty_max);

class Ipo final : public FirstOrderAlgorithm {
 public:
  // Throws std::invalid_argument unless alg is ipo and ipo_kappa, ipo_penalty_max are positive.
  explicit Ipo(const RunConfig& config);

  std::string_view name() const override { return "ipo"; }
  PolicyUpdateResult update(const PolicyUpdateInputs& inputs) override;
};

}  // namespace bsg::algos
