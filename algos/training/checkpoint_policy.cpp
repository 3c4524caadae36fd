#include "algos/training/checkpoint_policy.h"

#include <stdexcept>
#include <string>

#include "algos/training/budget_decorator.h"
#include "algos/training/load_policy.h"
#include "algos/training/run_directory.h"
#include "algos/training/run_environment.h"

namespace bsg::algos {
namespace {

// A run's acting policy (load_policy.h) with its own random stream, restarted every episode.
class LoadedCheckpointPolicy final : public CheckpointPolicy {
 public:
  LoadedCheckpointPolicy(const std::filesystem::path& root, EvaluationActions actions, const std::string& name)
      : root_(root),
        policy_(load_policy(RunDirectory(root))),
        description_(run_env_description(policy_->config())),
        mode_(actions) {
    const RunConfig& config = policy_->config();
    if (budget_method(config.alg) == BudgetMethod::saute) {
      throw std::invalid_argument("checkpoint " + root.string() + ": a " + std::string(to_string(config.alg)) +
                                  " policy acts on its Saute budgets, which a dataset's observations do not hold");
    }
    description_text_ = "checkpoint " + (name.empty() ? root.string() : name) + " (" + std::string(to_string(config.alg)) + ", " +
                        config.env_id + ", epoch " + std::to_string(policy_->epochs_completed()) + " of " +
                        std::to_string(config.epochs) + ", seed " + std::to_string(config.seed) + ", " +
                        std::string(policy_->action_words(mode_)) + ")";
  }

  std::string description() const override { return description_text_; }
  const RunConfig& config() const override { return policy_->config(); }
  const envs::EnvDescription& env_description() const override { return description_; }
  void start_episode(std::uint64_t seed) override { noise_ = Rng(seed); }

  void act(std::span<const double> observation, std::span<double> action) override {
    if (static_cast<int>(observation.size()) != policy_->observation_size() ||
        static_cast<int>(action.size()) != policy_->action_size()) {
      throw std::invalid_argument("checkpoint " + root_.string() + ": its policy takes " +
                                  std::to_string(policy_->observation_size()) + " observations and gives " +
                                  std::to_string(policy_->action_size()) + " actions, the environment has " +
                                  std::to_string(observation.size()) + " and " + std::to_string(action.size()));
    }
    policy_->act(observation, mode_, noise_, action);
  }

 private:
  std::filesystem::path root_;
  std::unique_ptr<LoadedPolicy> policy_;
  envs::EnvDescription description_;
  ActionMode mode_;
  std::string description_text_;
  Rng noise_{0};
};

}  // namespace

std::unique_ptr<CheckpointPolicy> load_checkpoint_policy(const std::filesystem::path& run_directory,
                                                         EvaluationActions actions, const std::string& name) {
  return std::make_unique<LoadedCheckpointPolicy>(run_directory, actions, name);
}

}  // namespace bsg::algos
