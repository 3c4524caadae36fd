#include "algos/training/load_policy.h"

#include <stdexcept>
#include <string>

#include "algos/core/actor_critic.h"
#include "algos/core/actor_critic_acting.h"
#include "algos/core/constraint_costs.h"
#include "algos/off_policy/make_off_policy_learner.h"
#include "algos/offline/offline_batches.h"
#include "algos/offline/make_offline_algorithm.h"
#include "algos/off_policy/off_policy_acting.h"
#include "algos/off_policy/off_policy_learner.h"
#include "algos/training/budget_decorator.h"
#include "algos/training/exploration_noise.h"
#include "algos/training/make_algorithm.h"
#include "algos/training/off_policy_checkpoint.h"
#include "algos/training/offline_family.h"
#include "algos/training/run_start.h"
#include "algos/training/run_environment.h"
#include "algos/training/training_checkpoint.h"
#include "common/run_config_yaml.h"

namespace bsg::algos {
namespace {

// The environment's sizes, which the networks are built for before the checkpoint fills them
// (a Saute policy's observation holds its budgets: budget_decorator.h).
struct PolicySizes {
  int observation = 0;
  int action = 0;
};
PolicySizes sizes_of(const RunConfig& config) {
  const std::unique_ptr<envs::Env> env = decorate_for_budget(config, make_run_env(config));
  return {env->spec().observation_dim, env->spec().action_dim};
}

class LoadedOnPolicy final : public LoadedPolicy {
 public:
  LoadedOnPolicy(const RunDirectory& directory, const RunConfig& config, PolicySizes sizes)
      : LoadedOnPolicy(directory, config, make_actor_critic(config, sizes)) {}

  int observation_size() const override { return acting_.observation_size(); }
  int action_size() const override { return acting_.action_size(); }
  void act(std::span<const double> observation, ActionMode mode, Rng& noise, std::span<double> action) override {
    acting_.act(observation, mode, noise, action);
  }
  double sampled_action_std() const override { return actor_critic_->policy.std(); }
  std::string_view action_words(ActionMode mode) const override {
    return mode == ActionMode::sampled ? "sampled actions" : "mean actions";
  }
  std::optional<ObservationStandardization> observation_standardization() const override {
    if (!actor_critic_->standardize_observations) return std::nullopt;
    const RunningMeanStd& statistics = actor_critic_->observation_normalizer;
    return ObservationStandardization{statistics.mean(), statistics.std(), RunningMeanStd::kStdEpsilon,
                                      statistics.options().clip};
  }

 private:
  LoadedOnPolicy(const RunDirectory& directory, const RunConfig& config, std::unique_ptr<ActorCritic> ac)
      : LoadedPolicy(config, load(directory, config, *ac)), actor_critic_(std::move(ac)), acting_(*actor_critic_) {
    // Sampled actions use the sigma of the checkpoint's last epoch (mean actions ignore it).
    set_last_epoch_std(this->config(), epochs_completed(), actor_critic_->policy);
  }
  static std::unique_ptr<ActorCritic> make_actor_critic(const RunConfig& config, PolicySizes sizes) {
    Rng unused_init(0);  // the checkpoint overwrites every parameter
    return std::make_unique<ActorCritic>(sizes.observation, sizes.action, config, unused_init);
  }
  static int load(const RunDirectory& directory, const RunConfig& config, ActorCritic& actor_critic) {
    const std::unique_ptr<OnPolicyAlgorithm> algorithm = make_algorithm(config);
    return load_training_checkpoint(directory.checkpoint(), config, actor_critic, *algorithm).epochs_completed;
  }

  std::unique_ptr<ActorCritic> actor_critic_;
  ActorCriticActing acting_;
};

class LoadedOffPolicy final : public LoadedPolicy {
 public:
  LoadedOffPolicy(const RunDirectory& directory, const RunConfig& config, PolicySizes sizes)
      : LoadedOffPolicy(directory, config, make_learner(config, sizes)) {}

  int observation_size() const override { return acting_.observation_size(); }
  int action_size() const override { return acting_.action_size(); }
  void act(std::span<const double> observation, ActionMode mode, Rng& noise, std::span<double> action) override {
    acting_.act(observation, mode, noise, action);
  }
  double sampled_action_std() const override { return 0.0; }
  std::string_view action_words(ActionMode mode) const override {
    return mode == ActionMode::sampled ? "exploring actions" : "deterministic actions";
  }
  std::optional<ObservationStandardization> observation_standardization() const override { return std::nullopt; }

 private:
  LoadedOffPolicy(const RunDirectory& directory, const RunConfig& config, std::unique_ptr<OffPolicyLearner> learner)
      : LoadedPolicy(config, load_off_policy_checkpoint(directory.checkpoint(), config, *learner).progress.epochs_completed),
        learner_(std::move(learner)),
        acting_(*learner_) {}
  static std::unique_ptr<OffPolicyLearner> make_learner(const RunConfig& config, PolicySizes sizes) {
    const int cost_critics = ignores_cost(config.alg) ? 0 : constraint_count(config);
    Rng unused_init(0);  // the checkpoint overwrites every parameter
    return make_off_policy_learner(config, sizes.observation, sizes.action, cost_critics, unused_init);
  }

  std::unique_ptr<OffPolicyLearner> learner_;
  OffPolicyActing acting_;
};

class LoadedOffline final : public LoadedPolicy {
 public:
  LoadedOffline(const RunDirectory& directory, const RunConfig& config, PolicySizes sizes)
      : LoadedOffline(directory, config, make_algorithm(config, sizes)) {}

  int observation_size() const override { return algorithm_->acting().observation_size(); }
  int action_size() const override { return algorithm_->acting().action_size(); }
  void act(std::span<const double> observation, ActionMode mode, Rng& noise, std::span<double> action) override {
    algorithm_->acting().act(observation, mode, noise, action);
  }
  double sampled_action_std() const override { return 0.0; }
  std::string_view action_words(ActionMode /*both modes act alike*/) const override { return "deterministic actions"; }
  // Every offline algorithm standardises with the dataset's training rows' mean and standard
  // deviation, without an epsilon or a clip.
  std::optional<ObservationStandardization> observation_standardization() const override {
    const ObservationScaling& scaling = algorithm_->scaling();
    return ObservationStandardization{scaling.mean, scaling.std, 0.0, 0.0};
  }

 private:
  LoadedOffline(const RunDirectory& directory, const RunConfig& config, std::unique_ptr<OfflineAlgorithm> algorithm)
      : LoadedPolicy(config, load_offline_checkpoint(directory.checkpoint(), config, *algorithm).epochs_completed),
        algorithm_(std::move(algorithm)) {}
  static std::unique_ptr<OfflineAlgorithm> make_algorithm(const RunConfig& config, PolicySizes sizes) {
    Rng unused_init(0);  // the checkpoint overwrites every parameter and the standardisation
    const ObservationScaling placeholder{Eigen::VectorXd::Zero(sizes.observation), Eigen::VectorXd::Ones(sizes.observation)};
    return make_offline_algorithm(config, sizes.observation, sizes.action, placeholder, unused_init);
  }

  std::unique_ptr<OfflineAlgorithm> algorithm_;
};

}  // namespace

std::unique_ptr<LoadedPolicy> load_policy(const RunDirectory& directory) {
  check_is_run_directory(directory);
  const RunConfig config = load_resolved_run_config(directory.config(), training_env_ids());
  if (is_multi_agent(config.alg)) {
    throw std::invalid_argument(directory.root.string() + ": a multi-agent run (alg " + std::string(to_string(config.alg)) +
                                "); bsg collect and bsg.load_policy load single-agent policies only "
                                "(bsg eval evaluates it)");
  }
  const PolicySizes sizes = sizes_of(config);
  switch (algorithm_info(config.alg).family) {
    case AlgorithmFamily::trust_region:
    case AlgorithmFamily::first_order: return std::make_unique<LoadedOnPolicy>(directory, config, sizes);
    case AlgorithmFamily::off_policy: return std::make_unique<LoadedOffPolicy>(directory, config, sizes);
    case AlgorithmFamily::offline: return std::make_unique<LoadedOffline>(directory, config, sizes);
    case AlgorithmFamily::multi_agent: break;  // refused above
  }
  throw std::invalid_argument("load_policy: unknown family of " + std::string(to_string(config.alg)));
}

}  // namespace bsg::algos
