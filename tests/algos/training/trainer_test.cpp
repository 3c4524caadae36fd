// The training loop on a scripted environment (fast, no physics): the
// safety net for non-finite values keeps the last good checkpoint, and
// epochs resumed in process continue exactly.
#include <gtest/gtest.h>

#include <filesystem>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "../../test_support.h"
#include "algos/training/make_algorithm.h"
#include "algos/training/on_policy_trainer.h"
#include "algos/training/training_checkpoint.h"
#include "common/atomic_file.h"
#include "common/build_identity.h"
#include "../scripted_env.h"
#include "../scripted_training.h"

namespace fs = std::filesystem;
using bsg::testing::read_text_file;
using bsg::testing::ScriptedEnv;
using bsg::testing::TemporaryDirectory;
using bsg::testing::scripted_config;
using bsg::testing::sigma_of_each_epoch;

TEST(Trainer, RunsEveryEpochThenEvaluates) {
  TemporaryDirectory dir;
  bsg::algos::OnPolicyTrainer trainer(scripted_config(), bsg::algos::RunDirectory(dir.path() / "run"),
                               bsg::MpiContext::single_process(), {}, std::make_unique<ScriptedEnv>(100));
  const bsg::algos::TrainingOutcome outcome = trainer.run();
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
  bsg::algos::OnPolicyTrainer trainer(config, bsg::algos::RunDirectory(dir.path() / "run"), bsg::MpiContext::single_process(), {},
                               std::move(env));
  try {
    trainer.run();
    FAIL() << "expected a NonFiniteError";
  } catch (const bsg::algos::NonFiniteError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("reward"), std::string::npos) << message;
    EXPECT_NE(message.find("epoch 2"), std::string::npos) << message;
    EXPECT_NE(message.find("after 2 epochs"), std::string::npos) << message;
  }
  // The checkpoint still holds the state after epoch 1 (2 epochs completed) and loads.
  bsg::Rng rng(5);
  bsg::algos::ActorCritic loaded(3, 2, config, rng);
  auto algorithm = bsg::algos::make_algorithm(config);
  const bsg::algos::TrainingProgress progress =
      bsg::algos::load_training_checkpoint(dir.path() / "run" / "checkpoint.bin", config, loaded, *algorithm);
  EXPECT_EQ(progress.epochs_completed, 2);
  EXPECT_TRUE(loaded.policy.mean_net().parameters().allFinite());
}

TEST(Trainer, ResumingInProcessContinuesWithTheSameNumbersInBothDtypes) {
  for (const bsg::Dtype dtype : {bsg::Dtype::float32, bsg::Dtype::float64}) {
    SCOPED_TRACE(std::string(bsg::to_string(dtype)));
    TemporaryDirectory dir;
    bsg::RunConfig config = scripted_config();
    config.dtype = dtype;
    config.save_freq = 10;  // only the stop and the end save
    bsg::algos::OnPolicyTrainer whole(config, bsg::algos::RunDirectory(dir.path() / "whole"), bsg::MpiContext::single_process(),
                               {}, std::make_unique<ScriptedEnv>(100));
    whole.run();

    bsg::algos::TrainerOptions stop;
    stop.stop_after_epochs = 3;
    {
      bsg::algos::OnPolicyTrainer first(config, bsg::algos::RunDirectory(dir.path() / "split"), bsg::MpiContext::single_process(),
                                 stop, std::make_unique<ScriptedEnv>(100));
      const bsg::algos::TrainingOutcome outcome = first.run();
      EXPECT_FALSE(outcome.finished);
      EXPECT_EQ(outcome.epochs_completed, 3);
    }
    bsg::algos::TrainerOptions resume;
    resume.resume = true;
    bsg::algos::OnPolicyTrainer second(config, bsg::algos::RunDirectory(dir.path() / "split"), bsg::MpiContext::single_process(),
                                resume, std::make_unique<ScriptedEnv>(100));
    EXPECT_EQ(second.epochs_completed(), 3);
    second.run();
    EXPECT_EQ(second.actor_critic().policy.mean_net().parameters(),
              whole.actor_critic().policy.mean_net().parameters());
    EXPECT_EQ(second.actor_critic().value.net().parameters(), whole.actor_critic().value.net().parameters());
    EXPECT_EQ(second.actor_critic().cost_value.net().parameters(), whole.actor_critic().cost_value.net().parameters());
    EXPECT_EQ(second.algorithm().state(), whole.algorithm().state());
  }
}

TEST(Trainer, ARunRecordsItsBuildAndAResumeByAnotherBuildSaysSo) {
  TemporaryDirectory dir;
  bsg::RunConfig config = scripted_config();
  const bsg::algos::RunDirectory run(dir.path() / "run");
  bsg::algos::TrainerOptions stop;
  stop.stop_after_epochs = 2;
  bsg::algos::OnPolicyTrainer(config, run, bsg::MpiContext::single_process(), stop, std::make_unique<ScriptedEnv>(100)).run();
  EXPECT_EQ(read_text_file(run.build()), bsg::to_text(bsg::this_build()));

  const auto resume_log = [&] {
    std::ostringstream log;
    bsg::algos::TrainerOptions resume;
    resume.resume = true;
    resume.stop_after_epochs = 3;
    resume.log = &log;
    bsg::algos::OnPolicyTrainer(config, run, bsg::MpiContext::single_process(), resume, std::make_unique<ScriptedEnv>(100))
        .run();
    return log.str();
  };
  EXPECT_EQ(resume_log().find("another build"), std::string::npos);  // the same build: no note

  bsg::BuildIdentity other = bsg::this_build();
  // Any instruction set but this build's (a BSG_NATIVE=OFF build is itself SSE2).
  other.vector_instructions = bsg::this_build().vector_instructions == "SSE2" ? "AVX2 FMA" : "SSE2";
  bsg::write_file_atomically(run.build(), bsg::to_text(other));
  const std::string log = resume_log();
  EXPECT_NE(log.find("note: the run was started by another build (vector instructions " + other.vector_instructions +
                     " -> " + bsg::this_build().vector_instructions + ")"),
            std::string::npos)
      << log;
  EXPECT_EQ(read_text_file(run.build()), bsg::to_text(other));  // the record keeps the build that started the run
}

TEST(Trainer, AFloat32EpochMovesTheParametersAsTheFloat64EpochDoes) {
  // Same seeds, different batch arithmetic: the first epoch's rollout is
  // identical (the rollout's one-sample passes are double in both), so after
  // one epoch the parameters differ only by single-precision rounding in the
  // update, a tiny fraction of how far the epoch moved them; a bug in the
  // float32 path would show as a gap of the order of the move itself.
  TemporaryDirectory dir;
  bsg::RunConfig config = scripted_config();
  config.epochs = 1;
  config.eval_episodes = 0;
  config.dtype = bsg::Dtype::float64;
  const bsg::algos::OnPolicyTrainer initial(config, bsg::algos::RunDirectory(dir.path() / "initial"),
                                     bsg::MpiContext::single_process(), {}, std::make_unique<ScriptedEnv>(100));
  bsg::algos::OnPolicyTrainer reference(config, bsg::algos::RunDirectory(dir.path() / "f64"), bsg::MpiContext::single_process(), {},
                                 std::make_unique<ScriptedEnv>(100));
  reference.run();
  config.dtype = bsg::Dtype::float32;
  bsg::algos::OnPolicyTrainer single(config, bsg::algos::RunDirectory(dir.path() / "f32"), bsg::MpiContext::single_process(), {},
                              std::make_unique<ScriptedEnv>(100));
  single.run();
  // The policy step (gradient, CG on Fisher products, line search) agrees to
  // 1e-3 of its length. The value nets get a looser bound: the scripted
  // observations are not normalised in epoch 0 (t/10 up to 10), which
  // saturates some tanh units; float32 rounds their derivative to exactly 0
  // where float64 keeps ~1e-9, and Adam, dividing by sqrt(v), turns such tiny
  // gradients into steps of size lr. value_function_test checks the value
  // fit itself at 1e-3 on unsaturated data.
  const auto check = [](const char* net, const Eigen::VectorXd& start, const Eigen::VectorXd& f64,
                        const Eigen::VectorXd& f32, double tolerance) {
    const double moved = (f64 - start).norm();
    EXPECT_GT(moved, 1e-3) << net;
    EXPECT_LT((f32 - f64).norm(), tolerance * moved) << net << " moved " << moved;
  };
  const auto& a0 = initial.actor_critic();
  const auto& a64 = reference.actor_critic();
  const auto& a32 = single.actor_critic();
  check("policy", a0.policy.mean_net().parameters(), a64.policy.mean_net().parameters(),
        a32.policy.mean_net().parameters(), 1e-3);
  check("V", a0.value.net().parameters(), a64.value.net().parameters(), a32.value.net().parameters(), 0.1);
  check("V_C", a0.cost_value.net().parameters(), a64.cost_value.net().parameters(),
        a32.cost_value.net().parameters(), 0.1);
}

TEST(Trainer, AnAnnealingThatEndsEarlyHoldsSigmaAtItsMinimum) {
  // E = 5, exploration_anneal_epochs = 2: sigma 0.509, 0.2595, then 0.01 in epochs 2-4
  // (the original schedule would end at 0.499/5 + 0.01 = 0.1098).
  bsg::RunConfig config = scripted_config();
  config.exploration_anneal_epochs = 2;
  config.eval_episodes = 0;
  const std::vector<double> sigmas = sigma_of_each_epoch(config);
  ASSERT_EQ(sigmas.size(), 5u);
  const double expected[5] = {0.509, 0.2595, 0.01, 0.01, 0.01};
  for (int k = 0; k < 5; ++k) EXPECT_NEAR(sigmas[static_cast<std::size_t>(k)], expected[k], 1e-15) << k;
}
