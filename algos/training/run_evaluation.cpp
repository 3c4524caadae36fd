#include "algos/training/run_evaluation.h"

#include <stdexcept>
#include <string>

#include "algos/training/budget_decorator.h"
#include "algos/training/exploration_noise.h"
#include "algos/training/load_policy.h"
#include "algos/training/run_environment.h"

namespace bsg::algos {

RunEvaluation evaluate_run_directory(const RunDirectory& directory, std::optional<int> episodes,
                                     const MpiContext& mpi) {
  return evaluate_run_directory(directory, episodes, mpi, {});
}

RunEvaluation evaluate_run_directory(const RunDirectory& directory, std::optional<int> episodes,
                                     const MpiContext& mpi, const EnvDecorator& decorate,
                                     std::optional<EvaluationActions> actions, std::optional<std::int64_t> seed) {
  const std::unique_ptr<LoadedPolicy> policy = load_policy(directory);
  const RunConfig& config = policy->config();
  const ActionMode mode = actions.value_or(evaluation_actions(config));
  // The off-policy actors evaluate deterministically (their exploring actions are for collecting).
  if (mode == ActionMode::sampled && policy->sampled_action_std() == 0.0) {
    throw std::invalid_argument("sampled evaluation actions are for the on-policy Gaussian policies; " +
                                std::string(to_string(config.alg)) + " evaluates its deterministic actor");
  }
  std::unique_ptr<envs::Env> env = make_run_env(config);
  StepCostSelector costs(config);
  if (costs.needs_terms()) costs.bind(env->spec().cost_term_names, env->spec().id);
  if (decorate) env = decorate(std::move(env));
  env = decorate_for_budget(config, std::move(env));  // a Saute policy acts on its budgets as in training
  RunEvaluation result;
  result.epochs_completed = policy->epochs_completed();
  result.epochs = config.epochs;
  result.summary =
      evaluate_policy(*env, *policy, episodes.value_or(config.eval_episodes), seed.value_or(config.seed), config.max_ep_len, mpi, costs,
                      {}, mode);
  if (mode == ActionMode::sampled) result.summary.action_std = policy->sampled_action_std();
  return result;
}

}  // namespace bsg::algos
