#include "algos/training/run_evaluation.h"

#include <stdexcept>
#include <string>

#include "algos/core/actor_critic.h"
#include "algos/training/exploration_noise.h"
#include "algos/training/make_algorithm.h"
#include "algos/off_policy/make_off_policy_learner.h"
#include "algos/training/off_policy_checkpoint.h"
#include "algos/training/off_policy_evaluation.h"
#include "algos/training/run_environment.h"
#include "algos/training/training_checkpoint.h"
#include "common/run_config_yaml.h"

namespace bsg::algos {

RunEvaluation evaluate_run_directory(const RunDirectory& directory, std::optional<int> episodes,
                                     const MpiContext& mpi) {
  return evaluate_run_directory(directory, episodes, mpi, {});
}

RunEvaluation evaluate_run_directory(const RunDirectory& directory, std::optional<int> episodes,
                                     const MpiContext& mpi, const EnvDecorator& decorate,
                                     std::optional<EvaluationActions> actions) {
  check_is_run_directory(directory);
  const RunConfig config = load_resolved_run_config(directory.config(), envs::registered_ids());
  std::unique_ptr<envs::Env> env = make_run_env(config);
  if (is_off_policy(config.alg)) {
    // The deterministic actor of the checkpoint (off_policy_evaluation.h).
    if (actions.value_or(EvaluationActions::mean) == EvaluationActions::sampled) {
      throw std::invalid_argument("sampled evaluation actions are for the on-policy Gaussian policies; " +
                                  std::string(to_string(config.alg)) + " evaluates its deterministic actor");
    }
    StepCostSelector costs(config);
    if (costs.needs_terms()) costs.bind(env->spec().cost_term_names, env->spec().id);
    const int cost_critics = ignores_cost(config.alg) ? 0 : constraint_count(config);
    Rng unused_init(0);  // the checkpoint overwrites every parameter
    const std::unique_ptr<OffPolicyLearner> learner = make_off_policy_learner(
        config, env->spec().observation_dim, env->spec().action_dim, cost_critics, unused_init);
    const OffPolicyCheckpoint saved = load_off_policy_checkpoint(directory.checkpoint(), config, *learner);
    RunEvaluation result;
    result.epochs_completed = saved.progress.epochs_completed;
    result.epochs = config.epochs;
    if (decorate) env = decorate(std::move(env));
    result.summary = evaluate_off_policy(*env, *learner, episodes.value_or(config.eval_episodes), config.seed,
                                         config.max_ep_len, mpi, costs);
    return result;
  }
  Rng unused_init(0);  // the checkpoint overwrites every parameter
  ActorCritic actor_critic(env->spec().observation_dim, env->spec().action_dim, config, unused_init);
  std::unique_ptr<OnPolicyAlgorithm> algorithm = make_algorithm(config);
  const TrainingProgress progress = load_training_checkpoint(directory.checkpoint(), config, actor_critic, *algorithm);
  RunEvaluation result;
  result.epochs_completed = progress.epochs_completed;
  result.epochs = config.epochs;
  StepCostSelector costs(config);
  if (costs.needs_terms()) costs.bind(env->spec().cost_term_names, env->spec().id);
  if (decorate) env = decorate(std::move(env));
  const EvaluationActions chosen = actions.value_or(evaluation_actions(config));
  if (chosen == EvaluationActions::sampled) set_last_epoch_std(config, progress.epochs_completed, actor_critic.policy);
  result.summary = evaluate_policy(*env, actor_critic, episodes.value_or(config.eval_episodes), config.seed,
                                   config.max_ep_len, mpi, costs, {}, chosen);
  return result;
}

}  // namespace bsg::algos
