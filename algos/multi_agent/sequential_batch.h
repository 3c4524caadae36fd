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

// Throws std::invalid_argument naming the agent and the field unless there is one batch per
// policy, every batch has the same N > 0 rows in all five fields, and its widths match its
// policy's d_o and d_a.
void check_agent_batches(std::span<const AgentBatch> batches, std::span<const GaussianPolicy> policies);

}  // namespace bsg::algos
