// Which budget decorator a run's environment wears (docs/algorithms.md#budget-methods): the
// training's choice, by `alg`, of the environment decorators in envs/ that change what the
// learner sees. Saute (ppo-saute, trpo-saute: envs/saute_env.h) puts the budget left in the
// observation and penalises the reward once it is spent, Simmer (ppo-simmer, trpo-simmer) is Saute
// with budgets that a controller moves between epochs (simmer_algorithm.h); early termination (ppo-early-terminated,
// trpo-early-terminated: envs/early_terminated_env.h) ends the learner's episode when it is spent.
// There is one budget per constraint, its limit d_i; the costs are the constraints' own
// (algos/core/constraint_costs.h). Training, its final evaluation and load_policy (`bsg eval`)
// decorate through this one function, so that a Saute policy acts on the observation it was
// trained on; rewards, costs and episode ends in logs and evaluations stay the environment's.
#pragma once

#include <memory>

#include "algos/core/algorithm.h"
#include "common/run_config.h"
#include "envs/env.h"

namespace bsg::algos {

enum class BudgetMethod { none, saute, early_termination };

BudgetMethod budget_method(Algorithm alg);

// `env` in the decorator of config.alg, or `env` itself (none). Saute's limits must be positive
// (check_run_config_relations refuses others, naming the key; the decorator throws
// std::invalid_argument on one that slipped through).
std::unique_ptr<envs::Env> decorate_for_budget(const RunConfig& config, std::unique_ptr<envs::Env> env);

// Simmer (ppo-simmer, trpo-simmer: simmer_algorithm.h): the next episodes of `env`, the run's
// Saute environment, start at the budgets the algorithm's controllers hold; nothing for an
// algorithm without a schedule. The on-policy family calls it before each epoch's rollout.
void apply_budget_schedule(const OnPolicyAlgorithm& algorithm, envs::Env& env);
// A Saute environment's next episodes start with their whole budgets (z_i,0 = 1, the limits d_i):
// the evaluation of a Simmer policy, as bsg eval's (OmniSafe's evaluator also starts at z = 1).
void restore_whole_budgets(envs::Env& env);

}  // namespace bsg::algos
