// What one agent brings to a sequential update (HAPPO, MACPO): the rank's samples of its own
// observations and actions, the behaviour policy's log-probabilities and its advantages. The
// family fills one per agent from its rollout.
//
// Row i of every agent's batch must be the same joint step (the same environment and time), as
// SafePO's buffers are indexed (episode_length, n_rollout_threads): the correction factor of row
// i multiplies the ratios of the agents already updated at that step.
#pragma once

#include <Eigen/Core>
#include <span>

#include "algos/core/gaussian_policy.h"

namespace bsg::algos {

struct AgentBatch {
  Eigen::MatrixXd observations;     // N x d_o, as the agent's policy sees them (normalised)
  Eigen::MatrixXd actions;          // N x d_a, the actions taken (unclipped)
  Eigen::VectorXd old_log_probs;    // N: log pi_old(a_i|o_i), the behaviour policy's, summed over d_a
  Eigen::VectorXd advantages;       // N: A_i (standardised as the family chooses)
  Eigen::VectorXd cost_advantages;  // N: A^C_i (MACPO's; HAPPO reads none, zeros will do)
};

// Throws std::invalid_argument naming agent `agent` and the field unless all five fields of
// `batch` have `rows` > 0 rows and its widths match the policy's d_o and d_a.
void check_agent_batch(const AgentBatch& batch, const GaussianPolicy& policy, std::size_t agent, Eigen::Index rows);

// The same for every agent with agent 0's N, after checking that there is one batch per policy
// and no policy is null. (The policies are pointers: a family keeps each in its agent's
// ActorCritic.)
void check_agent_batches(std::span<const AgentBatch> batches, std::span<GaussianPolicy* const> policies);

}  // namespace bsg::algos
