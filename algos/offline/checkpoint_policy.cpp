#include "algos/offline/checkpoint_policy.h"

#include <Eigen/Core>
#include <stdexcept>

#include "algos/core/actor_critic.h"
#include "algos/core/constraint_costs.h"
#include "algos/off_policy/make_off_policy_learner.h"
#include "algos/off_policy/off_policy_learner.h"
#include "algos/training/off_policy_checkpoint.h"
#include "algos/training/exploration_noise.h"
#include "algos/training/make_algorithm.h"
#include "algos/training/run_directory.h"
#include "algos/training/run_environment.h"
#include "algos/training/training_checkpoint.h"
#include "common/algorithms.h"
#include "common/run_config_yaml.h"

namespace bsg::algos {
namespace {

class LoadedCheckpointPolicy final : public CheckpointPolicy {
 public:
  LoadedCheckpointPolicy(const std::filesystem::path& root, EvaluationActions actions)
      : directory_(root),
        config_(load_checked_config(directory_)),
        description_(run_env_description(config_)),
        actions_(actions),
        actor_critic_(make_actor_critic(config_)) {
    std::unique_ptr<OnPolicyAlgorithm> algorithm = make_algorithm(config_);
    const TrainingProgress progress =
        load_training_checkpoint(directory_.checkpoint(), config_, actor_critic_, *algorithm);
    if (actions_ == EvaluationActions::sampled) {
      set_last_epoch_std(config_, progress.epochs_completed, actor_critic_.policy);
    }
    description_text_ = "checkpoint " + root.string() + " (" + std::string(to_string(config_.alg)) + ", " + config_.env_id + ", epoch " +
                        std::to_string(progress.epochs_completed) + " of " + std::to_string(config_.epochs) +
                        ", seed " + std::to_string(config_.seed) + ", " +
                        (actions_ == EvaluationActions::sampled ? "sampled actions" : "mean actions") + ")";
    raw_.resize(actor_critic_.observation_size());
    normalized_.resize(actor_critic_.observation_size());
    action_.resize(actor_critic_.action_size());
  }

  std::string description() const override { return description_text_; }
  const RunConfig& config() const override { return config_; }
  const envs::EnvDescription& env_description() const override { return description_; }
  void start_episode(std::uint64_t seed) override { noise_ = Rng(seed); }

  void act(std::span<const double> observation, std::span<double> action) override {
    if (static_cast<Eigen::Index>(observation.size()) != raw_.size() ||
        static_cast<Eigen::Index>(action.size()) != action_.size()) {
      throw std::invalid_argument("checkpoint " + directory_.root.string() + ": its policy takes " +
                                  std::to_string(raw_.size()) + " observations and gives " +
                                  std::to_string(action_.size()) + " actions, the environment has " +
                                  std::to_string(observation.size()) + " and " + std::to_string(action.size()));
    }
    raw_ = Eigen::Map<const Eigen::VectorXd>(observation.data(), raw_.size());
    actor_critic_.normalize_observation(raw_, normalized_);
    if (actions_ == EvaluationActions::sampled) {
      actor_critic_.policy.sample_action(normalized_, action_, noise_, workspace_);
    } else {
      actor_critic_.policy.mean_action(normalized_, action_, workspace_);
    }
    Eigen::Map<Eigen::VectorXd>(action.data(), action_.size()) = action_;
  }

 private:
  static RunConfig load_checked_config(const RunDirectory& directory) {
    check_is_run_directory(directory);
    return load_resolved_run_config(directory.config(), envs::registered_ids());
  }
  static ActorCritic make_actor_critic(const RunConfig& config) {
    const std::unique_ptr<envs::Env> env = make_run_env(config);
    Rng unused_init(0);  // the checkpoint overwrites every parameter
    return ActorCritic(env->spec().observation_dim, env->spec().action_dim, config, unused_init);
  }

  RunDirectory directory_;
  RunConfig config_;
  envs::EnvDescription description_;
  EvaluationActions actions_;
  ActorCritic actor_critic_;
  std::string description_text_;
  Rng noise_{0};
  Eigen::VectorXd raw_;
  Eigen::VectorXd normalized_;
  Eigen::VectorXd action_;
  MlpSampleWorkspace workspace_;
};

// The actor of an off-policy run (SAC, TD3, DDPG and their -lag forms):
// observations enter unnormalised, as the learner trained on them; the mean
// actions are its deterministic actor tanh(mu(s)), the sampled ones its
// exploring actions (SAC's squashed sample; TD3's and DDPG's Gaussian noise).
class LoadedOffPolicyCheckpointPolicy final : public CheckpointPolicy {
 public:
  LoadedOffPolicyCheckpointPolicy(const std::filesystem::path& root, RunConfig config, EvaluationActions actions)
      : directory_(root),
        config_(std::move(config)),
        description_(run_env_description(config_)),
        actions_(actions),
        learner_(make_learner(config_)) {
    const OffPolicyCheckpoint saved = load_off_policy_checkpoint(directory_.checkpoint(), config_, *learner_);
    description_text_ = "checkpoint " + root.string() + " (" + std::string(to_string(config_.alg)) + ", " +
                        config_.env_id + ", epoch " + std::to_string(saved.progress.epochs_completed) + " of " +
                        std::to_string(config_.epochs) + ", seed " + std::to_string(config_.seed) + ", " +
                        (actions_ == EvaluationActions::sampled ? "exploring actions" : "deterministic actions") +
                        ")";
    action_.resize(learner_->action_size());
  }

  std::string description() const override { return description_text_; }
  const RunConfig& config() const override { return config_; }
  const envs::EnvDescription& env_description() const override { return description_; }
  void start_episode(std::uint64_t seed) override { noise_ = Rng(seed); }

  void act(std::span<const double> observation, std::span<double> action) override {
    if (static_cast<int>(observation.size()) != learner_->observation_size() ||
        static_cast<int>(action.size()) != learner_->action_size()) {
      throw std::invalid_argument("checkpoint " + directory_.root.string() + ": its policy takes " +
                                  std::to_string(learner_->observation_size()) + " observations and gives " +
                                  std::to_string(learner_->action_size()) + " actions, the environment has " +
                                  std::to_string(observation.size()) + " and " + std::to_string(action.size()));
    }
    learner_->act(observation, actions_ == EvaluationActions::mean, noise_, action_);
    Eigen::Map<Eigen::VectorXd>(action.data(), action_.size()) = action_;
  }

 private:
  static std::unique_ptr<OffPolicyLearner> make_learner(const RunConfig& config) {
    const std::unique_ptr<envs::Env> env = make_run_env(config);
    const int cost_critics = ignores_cost(config.alg) ? 0 : constraint_count(config);
    Rng unused_init(0);  // the checkpoint overwrites every parameter
    return make_off_policy_learner(config, env->spec().observation_dim, env->spec().action_dim, cost_critics,
                                   unused_init);
  }

  RunDirectory directory_;
  RunConfig config_;
  envs::EnvDescription description_;
  EvaluationActions actions_;
  std::unique_ptr<OffPolicyLearner> learner_;
  std::string description_text_;
  Rng noise_{0};
  Eigen::VectorXd action_;
};

}  // namespace

std::unique_ptr<CheckpointPolicy> load_checkpoint_policy(const std::filesystem::path& run_directory,
                                                         EvaluationActions actions) {
  const RunDirectory directory(run_directory);
  check_is_run_directory(directory);
  RunConfig config = load_resolved_run_config(directory.config(), envs::registered_ids());
  if (is_off_policy(config.alg)) {
    return std::make_unique<LoadedOffPolicyCheckpointPolicy>(run_directory, std::move(config), actions);
  }
  return std::make_unique<LoadedCheckpointPolicy>(run_directory, actions);
}

}  // namespace bsg::algos
