// The cost budgets a training-time decorator keeps (envs/saute_env.h, envs/early_terminated_env.h):
// one per constraint of the run, each with its limit d_i on the undiscounted episode cost and its
// cost of a step. Which terms a constraint sums is the learner's to say (algos/core/
// constraint_costs.h), so the decorator is handed the selection as a function.
#pragma once

#include <functional>
#include <span>
#include <vector>

#include "envs/description/env_types.h"

namespace bsg::envs {

struct CostBudgets {
  std::vector<double> limits;  // d_i, one per budget
  // costs[i] = c_i of this step; costs has limits.size() entries. Must not allocate.
  std::function<void(const StepResult& step, std::span<double> costs)> step_costs;
};

}  // namespace bsg::envs
