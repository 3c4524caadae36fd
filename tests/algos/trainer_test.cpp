// The training loop on a scripted environment (fast, no physics): the
// safety net for non-finite values keeps the last good checkpoint, and
// epochs resumed in process continue exactly.
#include <gtest/gtest.h>

#include <filesystem>
#include <memory>

#include "../test_support.h"
#include "algos/make_algorithm.h"
#include "algos/trainer.h"
#include "algos/training_checkpoint.h"
#include "scripted_env.h"

namespace fs = std::filesystem;
using bsg::testing::read_text_file;
using bsg::testing::ScriptedEnv;
using bsg::testing::TemporaryDirectory;

namespace {

bsg::RunConfig scripted_config() {
  bsg::RunConfig config;
  config.env_id = "Scripted-v0";
  config.alg = bsg::Algorithm::lag_trpo;
  config.use_cost_value_function = true;
  config.hidden_sizes = {16, 16};
  config.epochs = 5;
  config.steps_per_epoch = 400;  // 4 episodes of 100 steps
  config.max_ep_len = 100;
  config.save_freq = 1;
  config.eval_episodes = 2;
  config.cost_limit = 5;
  return config;
}

}  // namespace

TEST(Trainer, RunsEveryEpochThenEvaluates) {
  TemporaryDirectory dir;
  bsg::OnPolicyTrainer trainer(scripted_config(), bsg::RunDirectory(dir.path() / "run"),
                               bsg::MpiContext::single_process(), {}, std::make_unique<ScriptedEnv>(100));
  const bsg::TrainingOutcome outcome = trainer.run();
  EXPECT_TRUE(outcome.finished);
  EXPECT_EQ(outcome.epochs_completed, 5);
  ASSERT_TRUE(outcome.evaluation.has_value());
  ASSERT_EQ(outcome.evaluation->episodes.size(), 2u);
  EXPECT_EQ(outcome.evaluation->episodes[0].episode_length, 100);
  EXPECT_NEAR(outcome.evaluation->mean_return, 100 + 0.01 * 5050, 1e-9);  // the scripted reward ignores actions
  EXPECT_NEAR(outcome.evaluation->mean_cost, 10.0, 1e-12);
  // Epoch 0's exploration noise is sigma_0 = 0.499 (1 - 0/5) + 0.01.
  const std::string progress = read_text_file(dir.path() / "run" / "progress.csv");
  EXPECT_NE(progress.find(",0.509,"), std::string::npos) << progress.substr(0, 400);
}

TEST(Trainer, ANonFiniteRewardStopsTheRunAndKeepsTheLastCheckpoint) {
  TemporaryDirectory dir;
  const bsg::RunConfig config = scripted_config();
  auto env = std::make_unique<ScriptedEnv>(100);
  env->nan_reward_after_steps = 2 * 400 + 50;  // in epoch 2
  bsg::OnPolicyTrainer trainer(config, bsg::RunDirectory(dir.path() / "run"), bsg::MpiContext::single_process(), {},
                               std::move(env));
  try {
    trainer.run();
    FAIL() << "expected a NonFiniteError";
  } catch (const bsg::NonFiniteError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("reward"), std::string::npos) << message;
    EXPECT_NE(message.find("epoch 2"), std::string::npos) << message;
    EXPECT_NE(message.find("after 2 epochs"), std::string::npos) << message;
  }
  // The checkpoint still holds the state after epoch 1 (2 epochs completed) and loads.
  bsg::Rng rng(5);
  bsg::ActorCritic loaded(3, 2, config, rng);
  auto algorithm = bsg::make_algorithm(config);
  const bsg::TrainingProgress progress =
      bsg::load_training_checkpoint(dir.path() / "run" / "checkpoint.bin", config, loaded, *algorithm);
  EXPECT_EQ(progress.epochs_completed, 2);
  EXPECT_TRUE(loaded.policy.mean_net().parameters().allFinite());
}

TEST(Trainer, ResumingInProcessContinuesWithTheSameNumbers) {
  TemporaryDirectory dir;
  bsg::RunConfig config = scripted_config();
  config.save_freq = 10;  // only the stop and the end save
  bsg::OnPolicyTrainer whole(config, bsg::RunDirectory(dir.path() / "whole"), bsg::MpiContext::single_process(), {},
                             std::make_unique<ScriptedEnv>(100));
  whole.run();

  bsg::TrainerOptions stop;
  stop.stop_after_epochs = 3;
  {
    bsg::OnPolicyTrainer first(config, bsg::RunDirectory(dir.path() / "split"), bsg::MpiContext::single_process(),
                               stop, std::make_unique<ScriptedEnv>(100));
    const bsg::TrainingOutcome outcome = first.run();
    EXPECT_FALSE(outcome.finished);
    EXPECT_EQ(outcome.epochs_completed, 3);
  }
  bsg::TrainerOptions resume;
  resume.resume = true;
  bsg::OnPolicyTrainer second(config, bsg::RunDirectory(dir.path() / "split"), bsg::MpiContext::single_process(),
                              resume, std::make_unique<ScriptedEnv>(100));
  EXPECT_EQ(second.epochs_completed(), 3);
  second.run();
  EXPECT_EQ(second.actor_critic().policy.mean_net().parameters(), whole.actor_critic().policy.mean_net().parameters());
  EXPECT_EQ(second.actor_critic().value.net().parameters(), whole.actor_critic().value.net().parameters());
  EXPECT_EQ(second.algorithm().state(), whole.algorithm().state());
}
