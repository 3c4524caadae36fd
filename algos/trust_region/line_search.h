// The two backtracking line searches of docs/algorithms.md#trpo-line-search and #constrained-line-search, reusable with any
// loss through callables. Trial j tries the step decay^j * Delta: the callable
// must set theta = theta_old + step, evaluate on the full LOCAL batch and
// return the local values; the search averages them over ranks (one fused
// allreduce per trial) so that every rank takes the same decision. The caller
// restores theta_old and applies the returned step.
//
// Non-finite values: the original tests finiteness rank-locally (A) or with
// "and" (B, quirk Q12); here a trial is rejected if any value on any rank is
// not finite (this project's default, Q12).
//
// Parameters:
//   budget            K: 15 (TRPO, TRPO-L, PDO), 20 (CPO, Q11), 25 (PCPO)
//   decay             0.8
//   target_kl         delta
//   kl_accept_factor  1.5 (Q13: accept KL <= 1.5 delta)
#pragma once

#include <Eigen/Core>
#include <functional>

#include "common/mpi_context.h"

namespace bsg::algos {

struct LineSearchOptions {
  int budget = 15;
  double decay = 0.8;
  double target_kl = 0.01;
  double kl_accept_factor = 1.5;
};

struct LineSearchResult {
  Eigen::VectorXd step;        // decay^j Delta if trial j was accepted, else 0
  int acceptance_step = 0;     // j + 1, or 0 if nothing was accepted
  double improvement = 0.0;    // avg(loss_old - loss_j) at the accepted trial
  double cost_change = 0.0;    // avg(L_C(theta_j) - L_C_old) (constrained search only)
  double kl = 0.0;             // avg KL at the accepted trial
  bool accepted() const { return acceptance_step > 0; }
};

// Line search A: local loss and KL at theta_old + step.
struct LossAndKl {
  double loss = 0.0;
  double kl = 0.0;
};
using LossEvaluator = std::function<LossAndKl(const Eigen::Ref<const Eigen::VectorXd>& step)>;

// Accepts the first j with finite loss, avg(loss_old - loss_j) >= 0 and
// avg(KL_j) <= kl_accept_factor * target_kl.
LineSearchResult trpo_line_search(const Eigen::Ref<const Eigen::VectorXd>& full_step, double loss_old,
                                  const LossEvaluator& evaluate, const MpiContext& mpi,
                                  const LineSearchOptions& options);

// Line search B: local reward loss l_R, cost surrogate L_C and KL at theta_old + step.
struct ConstrainedTrial {
  double reward_loss = 0.0;
  double cost_surrogate = 0.0;
  double kl = 0.0;
};
using ConstrainedEvaluator = std::function<ConstrainedTrial(const Eigen::Ref<const Eigen::VectorXd>& step)>;

struct ConstrainedLineSearchInputs {
  double reward_loss_old = 0.0;             // l_R(theta_old)
  double cost_surrogate_old = 0.0;          // L_C(theta_old)
  double constraint_violation = 0.0;        // c = (J_C - d) / (L + 1e-8)
  bool require_reward_improvement = true;   // CPO case >= 2; PCPO: c < 0
};

// Rejects, in this order: any non-finite value; I_j < 0 (only if
// require_reward_improvement); D_j > max(-c, 0); K_j > kl_accept_factor * delta.
LineSearchResult constrained_line_search(const Eigen::Ref<const Eigen::VectorXd>& full_step,
                                         const ConstrainedLineSearchInputs& inputs,
                                         const ConstrainedEvaluator& evaluate, const MpiContext& mpi,
                                         const LineSearchOptions& options);

}  // namespace bsg::algos
