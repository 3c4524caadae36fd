#include "algos/training/budget_decorator.h"

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "algos/core/constraint_costs.h"
#include "algos/training/simmer_algorithm.h"
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
    case Algorithm::trpo_saute:
    case Algorithm::ppo_simmer:  // Saute's environment, its budgets scheduled (simmer_algorithm.h)
    case Algorithm::trpo_simmer: return BudgetMethod::saute;
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

void apply_budget_schedule(const OnPolicyAlgorithm& algorithm, envs::Env& env) {
  const auto* simmer = dynamic_cast<const SimmerAlgorithm*>(&algorithm);
  if (simmer == nullptr) return;
  auto* saute = dynamic_cast<envs::SauteEnv*>(&env);
  if (saute == nullptr) throw std::logic_error("apply_budget_schedule: " + std::string(simmer->name()) + " needs its Saute environment");
  saute->set_start_fractions(simmer->start_fractions());
}

void restore_whole_budgets(envs::Env& env) {
  auto* saute = dynamic_cast<envs::SauteEnv*>(&env);
  if (saute == nullptr) return;
  saute->set_start_fractions(std::vector<double>(saute->normalized_budgets().size(), 1.0));
}

}  // namespace bsg::algos
