// P3O, penalized proximal policy optimisation (docs/algorithms.md#p3o; Zhang, Shen, Yang, Chen,
// Yuan, Wang and Tao, IJCAI 2022), as OmniSafe's P3O: PPO's clipped reward loss plus an exact
// penalty on each constraint's cost surrogate. Per minibatch of the passes (first_order_update.h):
//   l = 1/n sum_i -min(rho_i A_i, clip(rho_i) A_i) + kappa sum_j ReLU(L_Cj + J_Cj - d_j)
//   L_Cj = 1/n sum_i max(rho_i A^Cj_i, clip(rho_i, 1 - eps, 1 + eps) A^Cj_i)   (p3o_cost_clip: true, the paper)
//   L_Cj = 1/n sum_i rho_i A^Cj_i                                             (p3o_cost_clip: false, OmniSafe's p3o.py)
// with J_Cj this epoch's mean episode cost. The ReLU holds a mean over the minibatch, so l is
// not a mean of per-sample losses: before each step L_Cj is evaluated on the minibatch (averaged
// over ranks, so every rank, and one process on the ranks' data, switches the same penalties on),
// and the step takes the gradient of the per-sample loss
//   l_i = -min(rho_i A_i, clip(rho_i) A_i) + kappa sum_{j: L_Cj + J_Cj - d_j > 0} (the L_Cj term of sample i).
// As OmniSafe, J_Cj - d_j enters undiscounted and unscaled; the paper's (1 - gamma)(J_Cj - d_j)
// is for a discounted J_C. P3O keeps no multiplier: kappa is fixed.
//
// Columns: p3o_penalty, the mean over the update's steps of kappa sum_j ReLU(L_Cj + J_Cj - d_j)
// (OmniSafe's Loss/Loss_pi_cost).
// Parameters (RunConfig): clip, the first-order keys, p3o_kappa 20 (OmniSafe's P3O.yaml),
// p3o_cost_clip, cost_limit or constraints.
#pragma once

#include <Eigen/Core>
#include <span>
#include <vector>

#include "algos/first_order/first_order_algorithm.h"
#include "algos/first_order/first_order_update.h"
#include "common/mpi_context.h"
#include "common/run_config.h"

namespace bsg::algos {

// Sample i's term of L_C for cost_advantages[i] (which must outlive the function):
// max(rho_i A^C_i, clip(rho_i, 1 - clip, 1 + clip) A^C_i) if clipped, else rho_i A^C_i.
SampleLossFunction p3o_cost_surrogate(const Eigen::VectorXd& cost_advantages, double clip, bool clipped);

// The penalty of a minibatch: which ReLUs are on, and the per-sample loss they give.
class P3oPenalty {
 public:
  // violations: J_Cj - d_j, one per column of the surrogate's cost advantages.
  P3oPenalty(const PolicySurrogate& surrogate, std::vector<double> violations, double kappa, double clip,
             bool cost_clip);
  // Its loss functions refer to its own members.
  P3oPenalty(const P3oPenalty&) = delete;
  P3oPenalty& operator=(const P3oPenalty&) = delete;

  // Before a step (collective): L_Cj of the rows at the policy's parameters, averaged over ranks,
  // and the ReLUs' states. Returns kappa sum_j ReLU(L_Cj + J_Cj - d_j).
  double evaluate(SampleLossBatch& batch, const GaussianPolicy& policy, std::span<const Eigen::Index> rows,
                  const MpiContext& mpi);
  // Whether constraint j's ReLU was on at the last evaluate().
  bool active(std::size_t j) const { return active_.at(j); }

  // l_i of the clipped reward loss on `advantages` (which must outlive the function) plus kappa
  // times sample i's L_Cj term of every active constraint.
  SampleLossFunction sample_loss(const Eigen::VectorXd& advantages) const;

 private:
  std::vector<Eigen::VectorXd> cost_advantages_;  // A^Cj, one vector per constraint
  std::vector<double> violations_;
  double kappa_;
  double clip_;
  std::vector<SampleLossFunction> cost_terms_;
  std::vector<bool> active_;
};

class P3o final : public FirstOrderAlgorithm {
 public:
  // Throws std::invalid_argument unless alg is p3o and p3o_kappa is positive.
  explicit P3o(const RunConfig& config);

  std::string_view name() const override { return "p3o"; }
  PolicyUpdateResult update(const PolicyUpdateInputs& inputs) override;
};

}  // namespace bsg::algos
