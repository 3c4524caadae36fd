// One round of a sequential multi-agent update (HAPPO, MACPO): the agents are updated one after
// another in the round's order, each agent's update seeing the correction factor M of the agents
// updated before it (sequential_correction.h). The agent's own step is a callback, so that HAPPO
// (PPO's passes) and MACPO (CPO's step) share the round: happo_update.h and macpo_update.h.
//
// For agent i_m at position m: its means and log-probabilities on its batch before the step, the
// step update_agent(i_m, M), its means and log-probabilities after, then M_i *= pi_new / pi_old
// (SafePO's Runner.train in safepo/multi_agent/happo.py and macpo.py: the same order of events).
#pragma once

#include <functional>
#include <span>
#include <vector>

#include "algos/core/algorithm.h"
#include "algos/core/gaussian_policy.h"
#include "algos/multi_agent/sequential_batch.h"
#include "algos/multi_agent/sequential_correction.h"

namespace bsg::algos {

// What one agent's step did in a round.
struct AgentRoundStatistics {
  int agent = 0;     // its index among the policies
  int position = 0;  // its place in the round's order, 0 first
  double kl = 0.0;   // KL(pi_before || pi_after) averaged over samples and action dims (docs/algorithms.md#mean-kl)
  double step_norm = 0.0;  // |theta_after - theta_before| (with a learned log sigma, of [theta, s])
  CorrectionFactorStatistics factor;  // the M the agent's step was given
  std::vector<NamedScalar> diagnostics;  // what its update reported (its algorithm's columns)
};

// The agent's step: changes *policies[agent] given M; returns its columns.
using AgentUpdate = std::function<std::vector<NamedScalar>(int agent, const CorrectionFactor& factor)>;

// Runs one round. Throws std::invalid_argument naming the problem if the batches do not fit the
// policies (check_agent_batches) or `order` is not a permutation of the agents; statistics in
// the round's order.
std::vector<AgentRoundStatistics> sequential_round(std::span<GaussianPolicy* const> policies,
                                                   std::span<const AgentBatch> batches, std::span<const int> order,
                                                   const AgentUpdate& update_agent);

}  // namespace bsg::algos
