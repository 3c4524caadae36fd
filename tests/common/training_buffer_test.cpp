// What a run's memory check and rank check say for each family
// (common/run_config_checks.h): the message names the key that holds the
// family's training data, and each family's rank rules apply to it alone.
#include <gtest/gtest.h>

#include <string>

#include "common/config_error.h"
#include "common/run_config.h"
#include "common/run_config_checks.h"

namespace bsg {
namespace {

RunConfig config_of(Algorithm alg) {
  RunConfig config;
  config.alg = alg;
  config.hidden_sizes = {8};  // a small network, so that the buffer dominates the estimate
  return config;
}

// The message of check_training_memory with 1 kB available.
std::string memory_message(const RunConfig& config) {
  try {
    check_training_memory(config, 10, 2, 2, AvailableMemory{1024.0, "a test's 1 kB"});
  } catch (const ConfigError& error) {
    return error.what();
  }
  return "";
}

TEST(TrainingBuffer, EachFamilyNamesTheKeyThatHoldsItsData) {
  RunConfig on_policy = config_of(Algorithm::lag_trpo);
  on_policy.steps_per_epoch = 32000;
  EXPECT_EQ(training_buffer(on_policy, 2).description, "the rollout buffer (16000 steps per rank)");
  const std::string rollout = memory_message(on_policy);
  EXPECT_EQ(rollout.rfind("steps_per_epoch = 32000 needs an estimated ", 0), 0u) << rollout;
  EXPECT_NE(rollout.find("(16000 steps per rank, hidden_sizes [8])"), std::string::npos) << rollout;
  EXPECT_NE(rollout.find("reduce steps_per_epoch or run on more ranks"), std::string::npos) << rollout;

  RunConfig off_policy = config_of(Algorithm::sac_lag);
  off_policy.off_policy.buffer_size = 1000000;
  EXPECT_EQ(training_buffer(off_policy, 2).description, "the replay buffer (1000000 transitions per rank)");
  const std::string replay = memory_message(off_policy);
  EXPECT_EQ(replay.rfind("buffer_size = 1000000 needs an estimated ", 0), 0u) << replay;
  EXPECT_NE(replay.find("(a replay buffer of 1000000 transitions per rank, hidden_sizes [8])"), std::string::npos)
      << replay;
  EXPECT_NE(replay.find("reduce buffer_size"), std::string::npos) << replay;
  EXPECT_EQ(replay.find("steps_per_epoch"), std::string::npos) << replay;

  RunConfig offline = config_of(Algorithm::bc_safe);
  offline.off_policy.batch_size = 512;
  EXPECT_EQ(training_buffer(offline, 1).description, "the batches (512 rows)");
}

TEST(TrainingBuffer, TheRankRulesAreEachFamilysOwn) {
  // On-policy: each rank's batch fills the value nets' minibatches (100 / 16 = 6 < 16).
  RunConfig on_policy = config_of(Algorithm::ppo_lag);
  on_policy.steps_per_epoch = 200;
  on_policy.max_ep_len = 100;
  EXPECT_THROW(check_run_config_for_ranks(on_policy, 2), ConfigError);
  EXPECT_NO_THROW(check_run_config_for_ranks(config_of(Algorithm::ppo_lag), 2));

  // Off-policy: no minibatch rule; the ranks' steps must split over num_envs.
  RunConfig off_policy = config_of(Algorithm::td3_lag);
  off_policy.steps_per_epoch = 200;
  off_policy.max_ep_len = 100;
  EXPECT_NO_THROW(check_run_config_for_ranks(off_policy, 2));
  off_policy.off_policy.num_envs = 3;
  EXPECT_THROW(check_run_config_for_ranks(off_policy, 2), ConfigError);

  // Offline: one rank, whatever steps_per_epoch says (it steps no environment).
  RunConfig offline = config_of(Algorithm::bc_all);
  offline.steps_per_epoch = 7;
  EXPECT_NO_THROW(check_run_config_for_ranks(offline, 1));
  EXPECT_THROW(check_run_config_for_ranks(offline, 2), ConfigError);
}

}  // namespace
}  // namespace bsg
