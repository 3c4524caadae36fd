// HAPPO, heterogeneous-agent PPO (Kuba et al. 2022, "Trust Region Policy Optimisation in
// Multi-Agent Reinforcement Learning"; SafePO's safepo/multi_agent/happo.py):
// the agents take PPO steps one after another in a random order (sequential_order.h), agent i_m
// on the loss
//   l(theta) = -1/N sum_i M_i min(rho_i A_i, clip(rho_i, 1 - eps, 1 + eps) A_i)
//   rho_i = pi_theta(a_i|o_i) / pi_old(a_i|o_i),  M_i the correction of the agents before it
// (sequential_correction.h). As M_i > 0, M_i min(x, y) = min(M_i x, M_i y): the loss is PPO's
// clipped loss (algos/first_order/ppo.h) on the advantages M_i A_i, and an agent's update is
// PPO's update (its minibatch passes with Adam, its clip and early stop) on a batch whose
// advantages are M A. With one agent (M = 1) HAPPO is PPO.
//
// SafePO computes -sum(factor * min(surr1, surr2)).mean() with the factor detached: the same loss
// and gradient. Its entropy bonus (entropy_coef: 0 in marl_cfg/happo/config.yaml, 0.01 in its
// mamujoco block) is not part of bsg's PPO and not here.
#pragma once

#include <Eigen/Core>
#include <span>
#include <vector>

#include "algos/core/algorithm.h"
#include "algos/core/gaussian_policy.h"
#include "algos/first_order/ppo.h"
#include "algos/multi_agent/sequential_batch.h"
#include "algos/multi_agent/sequential_correction.h"
#include "algos/multi_agent/sequential_round.h"
#include "common/mpi_context.h"
#include "common/random.h"

namespace bsg::algos {

// l(theta) above over the whole (local) batch at the policy's parameters; if `gradient` is given it
// is overwritten with dl/dtheta (dl/d[theta, s] with a learned log sigma). Throws
// std::invalid_argument on mismatched sizes.
double happo_clipped_loss(const GaussianPolicy& policy, const AgentBatch& batch, const CorrectionFactor& factor,
                          double clip, Eigen::VectorXd* gradient = nullptr);

// One agent's HAPPO update: `ppo` (alg ppo; the agent's own, whose Adam state persists from
// update to update) on the batch with advantages M A. Collective: every rank calls it.
PolicyUpdateResult happo_agent_update(Ppo& ppo, GaussianPolicy& policy, const AgentBatch& batch,
                                      const CorrectionFactor& factor, const MpiContext& mpi, Rng& minibatch_rng);

// One HAPPO round: happo_agent_update for each agent in `order`, ppos[k] updating *policies[k].
std::vector<AgentRoundStatistics> happo_round(std::span<GaussianPolicy* const> policies, std::span<Ppo* const> ppos,
                                              std::span<const AgentBatch> batches, std::span<const int> order,
                                              const MpiContext& mpi, Rng& minibatch_rng);

}  // namespace bsg::algos
