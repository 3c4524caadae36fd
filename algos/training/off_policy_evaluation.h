// Evaluation of an off-policy learner (docs/algorithms.md#the-off-policy-loop): episodes of the
// deterministic actor a = tanh(mu(s)), floor(total_episodes / R) per rank on its own environment,
// seeded once with derive_seed(run seed, evaluation_environment, rank) and then reset from its own
// stream, each until the environment terminates or truncates (or max_ep_len steps); J, H and each
// constraint's H_i are the undiscounted sums. Rank 0 gathers every rank's episodes in rank order.
// After training (off_policy_trainer.h) and in `bsg eval` (run_evaluation.h). Collective.
#pragma once

#include <cstdint>

#include "algos/core/constraint_costs.h"
#include "algos/off_policy/off_policy_learner.h"
#include "algos/training/evaluation.h"
#include "common/mpi_context.h"
#include "envs/env.h"

namespace bsg::algos {

EvaluationSummary evaluate_off_policy(envs::Env& env, OffPolicyLearner& learner, int total_episodes,
                                      std::int64_t run_seed, int max_ep_len, const MpiContext& mpi,
                                      const StepCostSelector& costs);

}  // namespace bsg::algos
