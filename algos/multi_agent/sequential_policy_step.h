// HAPPO's or MACPO's policy step of one epoch on the rank's rows, as the multi-agent family runs
// it (docs/multi_agent.md#sequential-agent-updates-happo-macpo): the agents' batches arrive with
// the advantages GAE left in them, and
//   1. each agent's advantages are standardised, A <- (A - mean) / (std + 1e-8), and its cost
//      advantages centred, over that agent's rows on every rank (SafePO standardises per agent's
//      buffer; algos/core/advantage_normalization.h);
//   2. MACPO: every agent's c = macpo_constraint_violation(J_C, cost_limit, gamma) on the team's J_C
//      (SafePO's return_aver_cost writes the team's mean episode cost into every agent's buffer);
//   3. one round in `order`: happo_round with each agent's own Ppo, or macpo_round.
// Every statistic of steps 1 and 2 is pooled over the ranks, so R ranks holding equal shares of the
// rows take the step one process takes on all of them (tests/algos/training/
// multi_agent_family_mpi_test.cpp).
#pragma once

#include <span>
#include <vector>

#include "algos/first_order/ppo.h"
#include "algos/multi_agent/sequential_batch.h"
#include "algos/multi_agent/sequential_round.h"
#include "common/mpi_context.h"
#include "common/random.h"
#include "common/run_config.h"

namespace bsg::algos {

struct SequentialPolicyStep {
  std::vector<AgentRoundStatistics> round;    // per agent, in agent order
  std::vector<double> constraint_violations;  // MACPO: c per agent; HAPPO: empty
};

// `batches[k]`: agent k's rank-local rows, its cost advantages empty when the rollout has none
// (HAPPO reads none: zeros are passed on). `team_mean_episode_cost`: J_C, already pooled over
// ranks (MACPO only). `ppos`: HAPPO's, one per agent; MACPO takes none. Collective.
SequentialPolicyStep sequential_policy_step(const RunConfig& config, std::vector<AgentBatch> batches,
                                            std::span<GaussianPolicy* const> policies, std::span<Ppo* const> ppos,
                                            double team_mean_episode_cost, std::span<const int> order,
                                            const MpiContext& mpi, Rng& minibatch_rng);

}  // namespace bsg::algos
