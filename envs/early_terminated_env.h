// The early-terminated MDP (Sun et al. 2021, "Safe Exploration by Solving Early Terminated MDP";
// OmniSafe's adapter/early_terminated_adapter.py): the learner's episode ends at the step where
// some constraint's cost so far exceeds its limit,
//
//   cut at step t  <=>  sum_{k <= t} c_i,k > d_i  for some i      (OmniSafe's strict '>')
//
// with a learner reward of 0 on that step (OmniSafe's). The step's reward, cost, terms and
// episode end stay the environment's; the cut is StepResult::learner (env_types.h), and the
// caller resets. The sums restart at every reset (OmniSafe's sum restarts only at a cut, so that
// there an episode inherits the cost of the uncut ones before it; the paper's is per episode).
// One budget per constraint; OmniSafe's is the one budget of the environment's cost.
#pragma once

#include <memory>
#include <span>
#include <vector>

#include "envs/cost_budgets.h"
#include "envs/decorated_env.h"

namespace bsg::envs {

class EarlyTerminatedEnv final : public DecoratedEnv {
 public:
  // Throws std::invalid_argument without budgets or with a limit that is negative or not finite.
  EarlyTerminatedEnv(std::unique_ptr<Env> inner, CostBudgets budgets);

  std::span<const double> reset(std::uint64_t seed) override { return start_episode(inner().reset(seed)); }
  std::span<const double> reset() override { return start_episode(inner().reset()); }
  std::span<const double> reset_to(const Layout& layout) override { return start_episode(inner().reset_to(layout)); }
  StepResult step(std::span<const double> action) override;

  // sum_k c_i,k since the last reset, one per budget.
  const std::vector<double>& episode_costs() const { return episode_costs_; }

 private:
  std::span<const double> start_episode(std::span<const double> observation);

  CostBudgets budgets_;
  std::vector<double> step_costs_;
  std::vector<double> episode_costs_;
};

}  // namespace bsg::envs
