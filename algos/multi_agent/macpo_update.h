// MACPO, multi-agent constrained policy optimisation (Gu et al. 2021, "Multi-Agent Constrained
// Policy Optimisation"; SafePO's safepo/multi_agent/macpo.py): HATRPO's sequential round
// in a random order (sequential_order.h, sequential_round.h), each agent's step a CPO step
// (algos/trust_region/cpo.h, single_constraint_cpo_update: its case analysis, recovery branch
// and constrained line search, unchanged) on the agent's own batch with
//   reward surrogate  L_R = 1/N sum_i rho_i M_i A_i
//   cost surrogate    L_C = 1/N sum_i rho_i M_i A^C_i
// (M the correction factor of the agents updated before it, sequential_correction.h: SafePO's
// trpo_update multiplies both advantages by the same factor_batch), the Fisher matrix and the
// line search's KL of the agent's own policy, and the agent's constraint value c. With one agent
// (M = 1) and CPO's c the step is CPO's, bit for bit.
//
// Where SafePO's macpo.py differs from bsg's CPO step, bsg's is kept and the setting named:
//   c = (J_C - d)(1 - gamma), and 1e-8 if exactly 0 (macpo_constraint_violation below), where
//     bsg's CPO has (J_C - d) / (L + 1e-8): the caller chooses c.
//   r = -g^T F^-1 b in the dual (its reward_loss_grad is -g): cpo_r_sign corrected.
//   The line search tries fraction_coef step_fraction^j of the step (0.1 x 0.5^j, j < searching_steps
//     = 10, the step's norm first capped at 0.5) and accepts KL < target_kl; bsg's tries
//     backtrack_decay^j of it (0.5 and backtrack_budget 10 for SafePO's) and accepts
//     KL <= kl_accept_factor target_kl (1 for SafePO's): the 0.1 and the cap are not reproduced.
//   Case 4 when b^T b <= 1e-8 (bsg: 1e-6); its KL sums over the action dimensions (bsg's means
//     over them, docs/algorithms.md#mean-kl), so target_kl means d_a times as much there.
#pragma once

#include <span>
#include <vector>

#include "algos/core/algorithm.h"
#include "algos/core/gaussian_policy.h"
#include "algos/multi_agent/sequential_batch.h"
#include "algos/multi_agent/sequential_correction.h"
#include "algos/multi_agent/sequential_round.h"
#include "algos/trust_region/cpo.h"
#include "common/mpi_context.h"
#include "common/run_config.h"

namespace bsg::algos {

// SafePO's constraint value of an agent (macpo.py, trpo_update's rescale_constraint_val):
// c = (J_C - d)(1 - gamma), replaced by 1e-8 when exactly 0. Throws std::invalid_argument if J_C
// is not finite or gamma is outside [0, 1].
double macpo_constraint_violation(double mean_episode_cost, double cost_limit, double gamma);

// One agent's MACPO step on its batch corrected by M, with its constraint value c and the
// trust-region settings of `config` (target_kl, cg_*, fvp_subsample, backtrack_*,
// kl_accept_factor, cpo_r_sign, cpo_clamp_a). Collective. On return the policy holds the
// accepted step (theta_old bit for bit if none).
struct MacpoAgentStep {
  SingleConstraintCpoUpdate update;
  std::vector<NamedScalar> diagnostics;  // CPO's columns (single_constraint_cpo_diagnostics)
};
MacpoAgentStep macpo_agent_step(GaussianPolicy& policy, const AgentBatch& batch, const CorrectionFactor& factor,
                                double constraint_violation, const RunConfig& config, const MpiContext& mpi);

// One MACPO round: macpo_agent_step for each agent in `order`, agent k with constraint_violations[k].
std::vector<AgentRoundStatistics> macpo_round(std::span<GaussianPolicy* const> policies,
                                              std::span<const AgentBatch> batches, std::span<const int> order,
                                              std::span<const double> constraint_violations, const RunConfig& config,
                                              const MpiContext& mpi);

}  // namespace bsg::algos
