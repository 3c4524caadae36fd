// The evaluation files of a run directory (docs/reproducing.md#evaluation): returns.csv and
// costs.csv with one value per line and no header, and evaluation.json:
//   {"mean_return": J, "mean_cost": H, "episodes": n, "mean_length": L}
// (with "action_std": sigma after it when the actions were sampled, sampled_evaluation; after an
// off-policy run's training "actions": "deterministic actor", naming what J and H acted with, and
// "exploring_policy": {"episodes", "mean_return", "mean_cost", "mean_length"}, the same episodes
// acted with the exploring policy)
// and for a multi-agent run "agents": [{"agent": "agent_0", "mean_return", "mean_cost"}, ...] (each
// agent's own; J and H are the agents' mean),
// and, after training (docs/algorithms.md#safety-during-training), the training cost and every
// constraint (docs/algorithms.md#several-constraints; without `constraints:` the one on the
// environment's cost against cost_limit):
//   "cumulative_cost": C, "cost_rate": C / steps,
//   "constraints": [{"terms": [...] or "all", "limit": d_i, "mean_cost": H_i,
//                    "holds": H_i <= d_i (null without episodes), "cumulative_cost",
//                    "cost_rate", "epochs_over_limit"}, ...],
//   "cost_terms": {"<term>": mean episode sum, ...}  (each of the environment's cost terms)
#pragma once

#include <string>
#include <vector>

#include "algos/training/evaluation.h"
#include "algos/training/run_directory.h"
#include "algos/training/training_cost.h"
#include "common/constraint_config.h"

namespace bsg::algos {

// What training adds to evaluation.json.
struct TrainingSafety {
  std::vector<ConstraintConfig> constraints{};  // effective_constraints(config)
  TrainingCost training_cost{};
  long long training_steps = 0;               // environment steps of the whole training
};

void write_evaluation_files(const RunDirectory& directory, const EvaluationSummary& summary,
                            const TrainingSafety* safety = nullptr);

// The JSON object of evaluation.json; with `per_episode` also the arrays
// "returns", "costs" and "lengths"; with `safety` the training cost and the constraints.
std::string evaluation_json(const EvaluationSummary& summary, bool per_episode, const TrainingSafety* safety = nullptr);

}  // namespace bsg::algos
