#include "algos/training/budget_decorator.h"

#include <utility>

#include "algos/core/constraint_costs.h"
#include "envs/early_terminated_env.h"
#include "envs/saute_env.h"

namespace bsg::algos {
namespace {

// The constraints' limits and their step costs, bound to the environment's cost terms.
envs::CostBudgets run_budgets(const RunConfig& config, const envs::Env& env) {
  StepCostSelector selector(config);
  if (selector.needs_terms()) selector.bind(env.spec().cost_term_names, env.spec().id);
  envs::CostBudgets budgets;
  for (int i = 0; i < selector.count(); ++i) budgets.limits.push_back(constraint_limit(config, i));
  budgets.step_costs = [selector](const envs::StepResult& step, std::span<double> costs) {
    selector.select(step, Eigen::Map<Eigen::VectorXd>(costs.data(), static_cast<Eigen::Index>(costs.size())));
  };
  return budgets;
}

}  // namespace

BudgetMethod budget_method(Algorithm alg) {
  switch (alg) {
    case Algorithm::ppo_saute:
    case Algorithm::trpo_saute: return BudgetMethod::saute;
    case Algorithm::ppo_early_terminated:
    case Algorithm::trpo_early_terminated: return BudgetMethod::early_termination;
    default: return BudgetMethod::none;
  }
}

std::unique_ptr<envs::Env> decorate_for_budget(const RunConfig& config, std::unique_ptr<envs::Env> env) {
  const BudgetMethod method = budget_method(config.alg);
  if (method == BudgetMethod::none || env == nullptr) return env;
  envs::CostBudgets budgets = run_budgets(config, *env);
  if (method == BudgetMethod::early_termination) {
    return std::make_unique<envs::EarlyTerminatedEnv>(std::move(env), std::move(budgets));
  }
  return std::make_unique<envs::SauteEnv>(
      std::move(env), std::move(budgets),
      envs::SauteOptions{config.budget.saute_gamma, config.budget.unsafe_reward, config.max_ep_len});
}

}  // namespace bsg::algos
