// Which budget decorator a run's environment wears (docs/algorithms.md#budget-methods): the
// training's choice, by `alg`, of the environment decorators in envs/ that change what the
// learner sees. Saute (ppo-saute, trpo-saute: envs/saute_env.h) puts the budget left in the
// observation and penalises the reward once it is spent; early termination (ppo-early-terminated,
// trpo-early-terminated: envs/early_terminated_env.h) ends the learner's episode when it is spent.
// There is one budget per constraint, its limit d_i; the costs are the constraints' own
// (algos/core/constraint_costs.h). Training, its final evaluation and load_policy (`bsg eval`)
// decorate through this one function, so that a Saute policy acts on the observation it was
// trained on; rewards, costs and episode ends in logs and evaluations stay the environment's.
#pragma once

#include <memory>

#include "common/run_config.h"
#include "envs/env.h"

namespace bsg::algos {

enum class BudgetMethod { none, saute, early_termination };

BudgetMethod budget_method(Algorithm alg);

// `env` in the decorator of config.alg, or `env` itself (none). Saute's limits must be positive
// (check_run_config_relations refuses others, naming the key; the decorator throws
// std::invalid_argument on one that slipped through).
std::unique_ptr<envs::Env> decorate_for_budget(const RunConfig& config, std::unique_ptr<envs::Env> env);

}  // namespace bsg::algos
