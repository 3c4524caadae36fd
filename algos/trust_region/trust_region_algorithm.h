// The natural-gradient update that TRPO, TRPO-L, PDO and CRPO share
// (docs/algorithms.md#algorithm-updates), written once; a variant is one small
// file that says which surrogate to climb:
//   0. plan_step():        the variant's decision for this epoch (e.g. a multiplier
//                          update first), giving the surrogate weights
//                          -l = w_R L_R + sum_j w_j L_Cj and whether to line-search
//   1. theta_old, mu_old and the surrogates at theta_old (begin_policy_update)
//   2. search_direction(): by default g_w = avg grad (w_R L_R + sum_j w_j L_Cj)
//                          (one allreduce); PDO overrides it with g - sum_j lambda_j b_j
//   3. x = CG(F, g_w), q = x^T F x, alpha = sqrt(2 delta / (q + 1e-8)), Delta = alpha x
//   4. line search A on l (budget backtrack_budget), or the full step without it
//   5. theta = theta_old + the accepted step
//   6. columns: the common five for l, TRPO's six, the direction's and the plan's own,
//      then the variant's own (append_own_diagnostics: the multipliers')
// CPO and PCPO solve a constrained problem per step and stay outside this base; they
// share its TRPO columns (append_trpo_diagnostics).
//
// Parameters (RunConfig): target_kl, cg_iters, cg_damping, fvp_subsample,
// backtrack_budget, backtrack_decay, kl_accept_factor.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "algos/core/algorithm.h"
#include "algos/trust_region/line_search.h"
#include "algos/trust_region/trust_region_steps.h"
#include "common/run_config.h"

namespace bsg::algos {

// The six TRPO columns shared by all trust-region algorithms (docs/algorithms.md#logged-columns), in order.
std::vector<std::string> trpo_diagnostic_names();

// Appends the values of those six columns, in that order: the line search's
// acceptance step and final step norm, alpha, |gradient|, x^T F x and |x|.
void append_trpo_diagnostics(std::vector<NamedScalar>& diagnostics, const LineSearchResult& search,
                             double alpha, double gradient_norm, double x_fisher_x,
                             double direction_norm);

// The surrogate a step climbs, -l = w_R L_R + sum_j w_j L_Cj: its gradient is the default
// search direction, l is the line search's loss and the logged Loss/Pi.
struct TrustRegionSurrogate {
  double reward_weight = 1.0;
  // One weight per constraint; empty: the reward surrogate alone, l = l_R = -L_R
  // (TRPO's own arithmetic, which does not read the cost advantages at all).
  std::vector<double> cost_weights;

  static TrustRegionSurrogate reward_only() { return {}; }
  bool is_reward_only() const { return cost_weights.empty(); }
};

// A variant's decision for one epoch.
struct TrustRegionPlan {
  TrustRegionSurrogate surrogate;
  bool line_search = true;  // false: apply the full step Delta (acceptance step 1)
  std::vector<double> lagrange_multipliers;  // this epoch's lambda_j, for a direction that reads them (PDO)
  std::vector<NamedScalar> own_columns;      // logged after the direction's own columns (CRPO's case)
};

// The direction CG solves for, with what the columns report of it.
struct SearchDirection {
  Eigen::VectorXd gradient;               // g_w, solved as F x = g_w
  double logged_gradient_norm = 0.0;      // the Misc/gradient_norm column
  std::vector<NamedScalar> own_columns;   // logged right after TRPO's six
};

class TrustRegionAlgorithm : public OnPolicyAlgorithm {
 public:
  PolicyUpdateResult update(const PolicyUpdateInputs& inputs) final;
  // The common five, TRPO's six, then own_diagnostic_names().
  std::vector<std::string> diagnostic_names() const final;

 protected:
  explicit TrustRegionAlgorithm(const RunConfig& config) : OnPolicyAlgorithm(config) {}

  // Step 0, before theta_old is taken (collective if it reads the batch).
  virtual TrustRegionPlan plan_step(const PolicyUpdateInputs& inputs) = 0;
  // Step 2 (collective). The default: the rank-averaged gradient of plan.surrogate.
  virtual SearchDirection search_direction(const PolicyUpdateInputs& inputs, const TrustRegionPlan& plan);
  // The variant's columns after TRPO's: its direction's own_columns, its plan's
  // own_columns, then what append_own_diagnostics() appends.
  virtual std::vector<std::string> own_diagnostic_names() const { return {}; }
  virtual void append_own_diagnostics(PolicyUpdateResult& /*result*/) const {}
};

// g_w = avg grad (w_R L_R + sum_j w_j L_Cj) at the policy's parameters (one allreduce of length P).
Eigen::VectorXd averaged_surrogate_gradient(const PolicyUpdateInputs& inputs, const TrustRegionSurrogate& surrogate);

}  // namespace bsg::algos
