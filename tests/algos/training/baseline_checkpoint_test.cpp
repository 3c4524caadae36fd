// Checkpoints written by the program before the off-policy learners became one file each over a
// base, and before the run header and Adam's state had one codec each (tests/data/checkpoints/,
// see its README.md): they still load, and saving what was loaded gives the file's payload again
// byte for byte, for both formats and every way an Adam state is stored (value nets and networks
// in binary, the first-order policy's and a multiplier's as named entries).
#include <gtest/gtest.h>

#include <filesystem>
#include <memory>
#include <string>

#include "algos/core/actor_critic.h"
#include "algos/core/constraint_costs.h"
#include "algos/off_policy/make_off_policy_learner.h"
#include "algos/training/make_algorithm.h"
#include "algos/training/off_policy_checkpoint.h"
#include "algos/training/run_environment.h"
#include "algos/training/training_checkpoint.h"
#include "common/checkpoint_file.h"
#include "common/run_config_yaml.h"
#include "envs/env.h"

namespace bsg::algos {
namespace {

namespace fs = std::filesystem;

fs::path baseline_run(const std::string& name) { return fs::path(BSG_TEST_DATA_DIR) / "checkpoints" / name; }

RunConfig config_of(const fs::path& run) {
  return load_resolved_run_config(run / "config.yaml", envs::registered_ids());
}

class OffPolicyBaselineCheckpoint : public ::testing::TestWithParam<std::string> {};

TEST_P(OffPolicyBaselineCheckpoint, LoadsAndSavesToTheSameBytes) {
  const fs::path run = baseline_run(GetParam());
  const RunConfig config = config_of(run);
  const envs::EnvSpec spec = make_run_env(config)->spec();
  const int cost_critics = ignores_cost(config.alg) ? 0 : constraint_count(config);
  Rng unused(0);
  const std::unique_ptr<OffPolicyLearner> learner =
      make_off_policy_learner(config, spec.observation_dim, spec.action_dim, cost_critics, unused);
  const OffPolicyCheckpoint state = load_off_policy_checkpoint(run / "checkpoint.bin", config, *learner);
  EXPECT_GT(state.progress.epochs_completed, 0);
  EXPECT_GT(learner->update_count(), 0);
  EXPECT_EQ(encode_off_policy_checkpoint(config, state, *learner), read_checkpoint_file(run / "checkpoint.bin"));
}

INSTANTIATE_TEST_SUITE_P(SacTd3Ddpg, OffPolicyBaselineCheckpoint, ::testing::Values("sac-lag", "td3-lag", "ddpg"),
                         [](const auto& info) {
                           std::string name = info.param;
                           for (char& c : name) c = c == '-' ? '_' : c;
                           return name;
                         });

class OnPolicyBaselineCheckpoint : public ::testing::TestWithParam<std::string> {};

TEST_P(OnPolicyBaselineCheckpoint, LoadsAndSavesToTheSameBytes) {
  const fs::path run = baseline_run(GetParam());
  const RunConfig config = config_of(run);
  const envs::EnvSpec spec = make_run_env(config)->spec();
  Rng unused(0);
  ActorCritic actor_critic(spec.observation_dim, spec.action_dim, config, unused);
  const std::unique_ptr<OnPolicyAlgorithm> algorithm = make_algorithm(config);
  const TrainingProgress progress = load_training_checkpoint(run / "checkpoint.bin", config, actor_critic, *algorithm);
  EXPECT_GT(progress.epochs_completed, 0);
  EXPECT_GT(actor_critic.value.optimizer().step_count(), 0);
  EXPECT_EQ(encode_training_checkpoint(config, progress, actor_critic, *algorithm),
            read_checkpoint_file(run / "checkpoint.bin"));
}

// PPO-Lag: the policy's Adam as step-then-moments entries after its Adam multiplier's
// moments-then-step entries; PDO: the Adam multiplier of a trust-region algorithm.
INSTANTIATE_TEST_SUITE_P(PpoLagPdo, OnPolicyBaselineCheckpoint, ::testing::Values("ppo-lag", "pdo"),
                         [](const auto& info) {
                           std::string name = info.param;
                           for (char& c : name) c = c == '-' ? '_' : c;
                           return name;
                         });

}  // namespace
}  // namespace bsg::algos
