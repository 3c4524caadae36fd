#include "algos/training/run_evaluation.h"

#include <stdexcept>
#include <string>

#include "algos/training/budget_decorator.h"
#include "algos/training/exploration_noise.h"
#include "algos/training/load_policy.h"
#include "algos/training/multi_agent_family.h"
#include "algos/training/multi_agent_trainer.h"
#include "algos/training/run_environment.h"
#include "algos/training/run_start.h"

namespace bsg::algos {

RunEvaluation evaluate_run_directory(const RunDirectory& directory, std::optional<int> episodes,
                                     const MpiContext& mpi) {
  return evaluate_run_directory(directory, episodes, mpi, {});
}

namespace {

// The multi-agent family rebuilt from the run's config, its checkpoint loaded, and its own final
// evaluation run: the training's evaluation.json for the same episodes and seed.
RunEvaluation evaluate_multi_agent_run(const RunDirectory& directory, const RunConfig& config,
                                       std::optional<int> episodes, const MpiContext& mpi,
                                       std::optional<std::int64_t> seed, const MultiAgentEnvDecorator& decorate) {
  std::unique_ptr<envs::MultiAgentEnv> env = make_run_multi_agent_env(config);
  if (decorate) env = decorate(std::move(env));
  MultiAgentFamily family(config, mpi, std::move(env));
  RunEvaluation result;
  result.epochs_completed = family.load_checkpoint(directory.checkpoint()).epochs_completed;
  result.epochs = config.epochs;
  result.summary = family.evaluate_mean_actions(episodes.value_or(config.eval_episodes), seed.value_or(config.seed));
  return result;
}

void refuse_multi_agent_options(const RunDirectory& directory, const RunConfig& config, bool sampled_actions,
                                bool single_agent_decorator_only) {
  if (!is_multi_agent(config.alg)) return;
  const std::string run = directory.root.string() + ": a multi-agent run (alg " + std::string(to_string(config.alg)) + ")";
  if (sampled_actions) throw std::invalid_argument(run + " evaluates its agents' mean actions; sampled actions do not apply");
  if (single_agent_decorator_only) {
    throw std::invalid_argument(run + " is evaluated and recorded by bsg eval; bsg.evaluate takes single-agent runs");
  }
}

}  // namespace

void check_multi_agent_evaluation(const RunDirectory& directory, bool sampled_actions) {
  refuse_multi_agent_options(directory, resumed_training_config(directory), sampled_actions, false);
}

RunEvaluation evaluate_run_directory(const RunDirectory& directory, std::optional<int> episodes,
                                     const MpiContext& mpi, const EnvDecorator& decorate,
                                     std::optional<EvaluationActions> actions, std::optional<std::int64_t> seed,
                                     const MultiAgentEnvDecorator& decorate_multi_agent) {
  const RunConfig run_config = resumed_training_config(directory);
  if (is_multi_agent(run_config.alg)) {
    refuse_multi_agent_options(directory, run_config, actions == ActionMode::sampled,
                               decorate && !decorate_multi_agent);
    return evaluate_multi_agent_run(directory, run_config, episodes, mpi, seed, decorate_multi_agent);
  }
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
