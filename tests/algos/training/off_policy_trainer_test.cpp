// The off-policy loop (docs/algorithms.md#the-off-policy-loop): a run stopped and resumed from its
// checkpoint (networks, optimisers, multipliers and the replay buffer) continues with the same
// numbers as an uninterrupted one, on the scripted environment, under both multiplier schedules; the
// final evaluation adds the exploring policy's episodes; the update schedule takes
// update_every * updates_per_step gradient steps per round after start_steps; and a short learning
// run per family (SAC-Lag, TD3-Lag, DDPG-Lag) on SafetyBallCircle-v0 lifts the return clearly
// above a random policy's.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <numeric>
#include <sstream>
#include <string>

#include "../../test_support.h"
#include "../scripted_env.h"
#include "algos/core/constraint_costs.h"
#include "algos/training/evaluation.h"
#include "algos/training/load_policy.h"
#include "algos/training/off_policy_trainer.h"
#include "algos/training/progress_csv_fields.h"
#include "algos/training/run_environment.h"
#include "algos/training/run_evaluation.h"
#include "common/config_error.h"
#include "common/run_config_checks.h"
#include "common/run_config_resolve.h"

namespace fs = std::filesystem;
using bsg::testing::ScriptedEnv;
using bsg::testing::TemporaryDirectory;

namespace {
namespace off_policy_trainer_test {

bsg::RunConfig scripted_config(bsg::Algorithm alg) {
  bsg::RunConfig config;
  config.env_id = "Scripted-v0";
  config.alg = alg;
  config.hidden_sizes = {16, 16};
  config.epochs = 5;
  config.steps_per_epoch = 200;  // 2 environments x 100 steps: episodes of 40 steps run across epochs
  config.max_ep_len = 40;
  config.save_freq = 3;          // checkpoints (and cut episodes) after epochs 3 and 5
  config.eval_episodes = 2;
  config.cost_limit = 1;
  config.off_policy.num_envs = 2;
  config.off_policy.start_steps = 100;
  config.off_policy.update_every = 10;
  config.off_policy.updates_per_step = 0.35;  // 3.5 per round: the fraction is carried
  config.off_policy.batch_size = 32;
  config.off_policy.buffer_size = 300;        // wraps around within the run
  config.off_policy.n_step = 2;
  config.off_policy.policy_delay = 2;
  config.off_policy.auto_alpha = true;
  config.multiplier.lambda_optimizer = bsg::LambdaOptimizer::adam;
  config.multiplier.lambda_lr = 0.05;
  config.dtype = bsg::Dtype::float64;
  return config;
}

std::vector<std::unique_ptr<bsg::envs::Env>> scripted_envs(int count) {
  std::vector<std::unique_ptr<bsg::envs::Env>> envs;
  for (int i = 0; i < count; ++i) envs.push_back(std::make_unique<ScriptedEnv>(40, std::nullopt, 3));
  return envs;
}

// progress.csv without its wall-clock columns.
std::string without_times(const fs::path& path) {
  const auto rows = bsg::testing::read_csv_rows(path);
  std::string text;
  std::vector<bool> keep;
  for (const std::string& name : rows.front()) {
    keep.push_back(name != "time_collect_s" && name != "time_update_s" && name != "time_s" && name != "fps");
  }
  for (const auto& row : rows) {
    for (std::size_t c = 0; c < row.size(); ++c) {
      if (keep[c]) text += row[c] + ",";
    }
    text += "\n";
  }
  return text;
}

// Both multiplier schedules: with update_round the window of recent episodes starts empty after the
// checkpoint in both runs.
TEST(OffPolicyTrainer, ResumingContinuesWithTheSameNumbers) {
  for (const bsg::Algorithm alg : {bsg::Algorithm::sac_lag, bsg::Algorithm::td3_lag, bsg::Algorithm::ddpg_lag})
  for (const bsg::MultiplierSchedule schedule : {bsg::MultiplierSchedule::epoch, bsg::MultiplierSchedule::update_round}) {
    SCOPED_TRACE(std::string(bsg::to_string(alg)) + (schedule == bsg::MultiplierSchedule::epoch ? " epoch" : " update_round"));
    TemporaryDirectory dir;
    bsg::RunConfig config = scripted_config(alg);
    config.off_policy.multiplier_schedule = schedule;
    config.off_policy.multiplier_window = 3;
    bsg::algos::OffPolicyTrainer whole(config, bsg::algos::RunDirectory(dir.path() / "whole"),
                                       bsg::MpiContext::single_process(), {}, scripted_envs(2));
    ASSERT_TRUE(whole.run().finished);
    bsg::algos::TrainerOptions stop;
    stop.stop_after_epochs = 3;
    {
      bsg::algos::OffPolicyTrainer first(config, bsg::algos::RunDirectory(dir.path() / "split"),
                                         bsg::MpiContext::single_process(), stop, scripted_envs(2));
      EXPECT_EQ(first.run().epochs_completed, 3);
    }
    bsg::algos::TrainerOptions resume;
    resume.resume = true;
    bsg::algos::OffPolicyTrainer second(config, bsg::algos::RunDirectory(dir.path() / "split"),
                                        bsg::MpiContext::single_process(), resume, scripted_envs(2));
    ASSERT_EQ(second.epochs_completed(), 3);
    ASSERT_EQ(second.buffer().total_added(), 3 * 200);  // the buffer came back with the checkpoint
    ASSERT_TRUE(second.run().finished);
    EXPECT_EQ(second.learner().actor().parameters(), whole.learner().actor().parameters());
    EXPECT_EQ(second.learner().update_count(), whole.learner().update_count());
    EXPECT_EQ(without_times(dir.path() / "split" / "progress.csv"), without_times(dir.path() / "whole" / "progress.csv"));
    EXPECT_EQ(bsg::testing::read_text_file(dir.path() / "split" / "returns.csv"),
              bsg::testing::read_text_file(dir.path() / "whole" / "returns.csv"));
    // the buffer's record holds the run's transitions once, not a copy per checkpoint
    EXPECT_EQ(fs::file_size(dir.path() / "split" / "replay_buffer.r0.log"),
              fs::file_size(dir.path() / "whole" / "replay_buffer.r0.log"));
  }
}

// A run killed after its buffer record grew but before checkpoint.bin was replaced (here: the
// epoch-3 checkpoint put back after epoch 4 was saved, and a torn record appended) resumes from
// the checkpoint it finds, cutting the later records off, and still ends as an uninterrupted run.
TEST(OffPolicyTrainer, AKilledRunResumesFromItsCheckpointDroppingLaterBufferRecords) {
  TemporaryDirectory dir;
  const bsg::RunConfig config = scripted_config(bsg::Algorithm::sac_lag);
  bsg::algos::OffPolicyTrainer whole(config, bsg::algos::RunDirectory(dir.path() / "whole"),
                                     bsg::MpiContext::single_process(), {}, scripted_envs(2));
  ASSERT_TRUE(whole.run().finished);
  const fs::path split = dir.path() / "split";
  for (const int stop_after : {3, 4}) {
    bsg::algos::TrainerOptions options;
    options.stop_after_epochs = stop_after;
    options.resume = stop_after == 4;
    bsg::algos::OffPolicyTrainer part(config, bsg::algos::RunDirectory(split), bsg::MpiContext::single_process(),
                                      options, scripted_envs(2));
    part.run();
    if (stop_after == 3) fs::copy_file(split / "checkpoint.bin", dir.path() / "checkpoint_after_3.bin");
  }
  fs::copy_file(dir.path() / "checkpoint_after_3.bin", split / "checkpoint.bin", fs::copy_options::overwrite_existing);
  const auto size_after_4 = fs::file_size(split / "replay_buffer.r0.log");
  bsg::testing::write_text_file(split / "replay_buffer.r0.log",
                                bsg::testing::read_text_file(split / "replay_buffer.r0.log") + "torn record");
  bsg::algos::TrainerOptions resume;
  resume.resume = true;
  bsg::algos::OffPolicyTrainer last(config, bsg::algos::RunDirectory(split), bsg::MpiContext::single_process(), resume,
                                    scripted_envs(2));
  ASSERT_EQ(last.epochs_completed(), 3);
  EXPECT_LT(fs::file_size(split / "replay_buffer.r0.log"), size_after_4);  // epoch 4's record is gone
  ASSERT_TRUE(last.run().finished);
  EXPECT_EQ(last.learner().actor().parameters(), whole.learner().actor().parameters());
  EXPECT_EQ(without_times(split / "progress.csv"), without_times(dir.path() / "whole" / "progress.csv"));
}

// `bsg eval` of an off-policy run directory re-runs the final evaluation from the checkpoint: the
// same episodes, so the same J and H as the run's evaluation.json.
TEST(OffPolicyTrainer, EvaluatingTheRunDirectoryRepeatsTheFinalEvaluation) {
  bsg::RunConfigRequest request;
  request.configs_dir = fs::path(BSG_SOURCE_DIR) / "configs";
  request.set_arguments = {"env_id=SafetyBallCircle-v0", "alg=sac-lag", "epochs=1", "steps_per_epoch=500",
                           "eval_episodes=3", "hidden_sizes=[8, 8]", "num_envs=1", "start_steps=100",
                           "update_every=50", "max_ep_len=100"};
  const bsg::RunConfig config = bsg::resolve_run_config(request).config;
  const TemporaryDirectory directory;
  const bsg::algos::RunDirectory run(directory.path() / "run");
  bsg::algos::OffPolicyTrainer trainer(config, run, bsg::MpiContext::single_process(), {});
  const bsg::algos::TrainingOutcome outcome = trainer.run();
  ASSERT_TRUE(outcome.evaluation.has_value());
  const bsg::algos::RunEvaluation again =
      bsg::algos::evaluate_run_directory(run, std::nullopt, bsg::MpiContext::single_process());
  EXPECT_EQ(again.epochs_completed, 1);
  ASSERT_EQ(again.summary.episodes.size(), 3u);
  EXPECT_EQ(again.summary.mean_return, outcome.evaluation->mean_return);
  EXPECT_EQ(again.summary.mean_cost, outcome.evaluation->mean_cost);
  const std::string json = bsg::testing::read_text_file(run.evaluation());
  EXPECT_TRUE(bsg::testing::contains(json, "\"mean_return\": " + bsg::algos::format_csv_number(again.summary.mean_return)));
  // The final evaluation sums the environment's cost terms, as an on-policy run's does: BallCircle's
  // one term is its cost, so its mean is H.
  ASSERT_EQ(outcome.evaluation->term_names, (std::vector<std::string>{"cost_outside_bounds"}));
  EXPECT_EQ(outcome.evaluation->mean_term_costs.at(0), outcome.evaluation->mean_cost);
  EXPECT_TRUE(bsg::testing::contains(json, "\"cost_terms\": {\"cost_outside_bounds\": "));
  // Beside the deterministic actor's J and H, the same episodes acted with the exploring policy:
  // those of the policy loaded from the checkpoint, sampling its actions.
  EXPECT_TRUE(bsg::testing::contains(json, "\"actions\": \"deterministic actor\""));
  ASSERT_TRUE(outcome.evaluation->exploring.has_value());
  const std::unique_ptr<bsg::algos::LoadedPolicy> policy = bsg::algos::load_policy(run);
  const std::unique_ptr<bsg::envs::Env> env = bsg::algos::make_run_env(config);
  const bsg::algos::EvaluationSummary exploring =
      bsg::algos::evaluate_policy(*env, *policy, 3, config.seed, config.max_ep_len, bsg::MpiContext::single_process(),
                                  bsg::algos::StepCostSelector(config), {}, bsg::algos::ActionMode::sampled);
  EXPECT_EQ(outcome.evaluation->exploring->episodes, 3);
  EXPECT_EQ(outcome.evaluation->exploring->mean_return, exploring.mean_return);
  EXPECT_EQ(outcome.evaluation->exploring->mean_cost, exploring.mean_cost);
  EXPECT_NE(exploring.mean_return, again.summary.mean_return);  // the noise acted
  EXPECT_TRUE(bsg::testing::contains(json, "\"exploring_policy\": {\"episodes\": 3, \"mean_return\": " +
                                               bsg::algos::format_csv_number(exploring.mean_return)));
}

TEST(OffPolicyTrainer, TakesUpdatesPerStepGradientStepsPerRoundAfterStartSteps) {
  TemporaryDirectory dir;
  bsg::RunConfig config = scripted_config(bsg::Algorithm::sac);
  config.epochs = 2;
  bsg::algos::OffPolicyTrainer trainer(config, bsg::algos::RunDirectory(dir.path() / "run"),
                                       bsg::MpiContext::single_process(), {}, scripted_envs(2));
  ASSERT_TRUE(trainer.run().finished);
  const auto progress = bsg::testing::read_csv_columns(dir.path() / "run" / "progress.csv");
  // Rounds of 2 steps (2 environments); a round of updates every 5 rounds (10 steps), owing
  // 10 x 0.35 = 3.5 gradient steps, paid 3, 4, 3, 4, ... Epoch 0: rounds r = 0..99 start at
  // step 2r; learning starts with the round that reaches start_steps = 100 (r = 49), so the
  // rounds of updates after r = 49, 54, ..., 99 count: 11 of them, 6 x 3 + 5 x 4 = 38 steps, 0.5
  // carried. Epoch 1: 20 rounds of updates from 0.5 carried: 4, 3, 4, ... = 10 x 4 + 10 x 3 = 70.
  EXPECT_EQ(progress.at("updates")[0], 38.0);
  EXPECT_EQ(progress.at("updates")[1], 70.0);
  // 100 steps per environment in epoch 0: 2 complete episodes of 40 steps each, the third runs on.
  EXPECT_EQ(progress.at("episodes")[0], 4.0);
  EXPECT_EQ(trainer.buffer().total_added(), 400);
  EXPECT_EQ(trainer.buffer().size(), 300);
}

// The ETA counts only epochs that take gradient steps throughout: with start_steps = 300 and 200
// steps per epoch, epochs 1 and 2 (starting at steps 0 and 200) are random and fast, so until
// epoch 3 (starting at 400) has been timed the line says the ETA is not known.
TEST(OffPolicyTrainer, TheEtaWaitsForAnEpochThatLearns) {
  TemporaryDirectory dir;
  bsg::RunConfig config = scripted_config(bsg::Algorithm::sac);
  config.epochs = 4;
  config.off_policy.start_steps = 300;
  std::ostringstream log;
  bsg::algos::TrainerOptions options;
  options.log = &log;
  bsg::algos::OffPolicyTrainer trainer(config, bsg::algos::RunDirectory(dir.path() / "run"),
                                       bsg::MpiContext::single_process(), options, scripted_envs(2));
  ASSERT_TRUE(trainer.run().finished);
  std::vector<std::string> epoch_lines;
  std::istringstream lines(log.str());
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("epoch ", 0) == 0) epoch_lines.push_back(line);
  }
  ASSERT_EQ(epoch_lines.size(), 4u) << log.str();
  for (int i : {0, 1}) EXPECT_TRUE(bsg::testing::contains(epoch_lines[i], "ETA once learning starts")) << epoch_lines[i];
  for (int i : {2, 3}) EXPECT_FALSE(bsg::testing::contains(epoch_lines[i], "once learning")) << epoch_lines[i];
  EXPECT_TRUE(bsg::testing::contains(epoch_lines[3], "ETA 0s")) << epoch_lines[3];
}

TEST(OffPolicyTrainer, EpochsShorterThanAnEpisodeCarryItsEpisodesOn) {
  // 10 steps per environment per epoch, episodes of 40: they end in epoch 3; the checkpoint after
  // epoch 4 cuts the next ones, which restart in epoch 5 and end after the run (epoch 8).
  TemporaryDirectory dir;
  bsg::RunConfig config = scripted_config(bsg::Algorithm::sac);
  config.epochs = 8;
  config.steps_per_epoch = 20;
  config.save_freq = 5;
  config.off_policy.start_steps = 40;
  config.off_policy.update_every = 5;
  EXPECT_NO_THROW(bsg::check_run_config_for_ranks(config, 1));
  bsg::algos::OffPolicyTrainer trainer(config, bsg::algos::RunDirectory(dir.path() / "run"),
                                       bsg::MpiContext::single_process(), {}, scripted_envs(2));
  ASSERT_TRUE(trainer.run().finished);
  const auto progress = bsg::testing::read_csv_columns(dir.path() / "run" / "progress.csv");
  EXPECT_EQ(progress.at("episodes"), (std::vector<double>{0, 0, 0, 2, 0, 0, 0, 0}));
}

TEST(OffPolicyConfig, RefusesCheckpointsTooCloseForAnEpisodeToEnd) {
  bsg::RunConfig config = scripted_config(bsg::Algorithm::sac);
  config.steps_per_epoch = 20;  // 10 steps per environment
  config.save_freq = 3;         // 30 steps between the checkpoints that cut episodes of 40
  try {
    bsg::check_run_config_for_ranks(config, 1);
    ADD_FAILURE() << "accepted";
  } catch (const bsg::ConfigError& e) {
    const std::string message = e.what();
    EXPECT_TRUE(bsg::testing::contains(message, "3 * 20 / (1 * 2) = 30 steps between checkpoints")) << message;
    EXPECT_TRUE(bsg::testing::contains(message, "max_ep_len = 40")) << message;
  }
  config.alg = bsg::Algorithm::trpo;  // the on-policy loop still needs an episode per epoch
  config.steps_per_epoch = 32;
  config.num_mini_batches = 1;
  try {
    bsg::check_run_config_for_ranks(config, 1);
    ADD_FAILURE() << "accepted";
  } catch (const bsg::ConfigError& e) {
    EXPECT_TRUE(bsg::testing::contains(e.what(), "max_ep_len = 40 exceeds the local steps per rank")) << e.what();
  }
}

TEST(OffPolicyConfig, RejectsBadValuesAndKeysOfOtherFamiliesWithOneLine) {
  bsg::RunConfigRequest request;
  request.configs_dir = fs::path(BSG_SOURCE_DIR) / "configs";
  request.valid_env_ids = {"SafetyBallCircle-v0"};
  for (const auto& [setting, named] : std::vector<std::pair<std::string, std::string>>{
           {"n_step=0", "n_step"}, {"polyak=1.5", "polyak"}, {"batch_size=0", "batch_size"},
           {"updates_per_step=-1", "updates_per_step"}, {"lam=0.9", "lam"}, {"noise_clip=0.3", "noise_clip"}}) {
    SCOPED_TRACE(setting);
    request.set_arguments = {"env_id=SafetyBallCircle-v0", "alg=sac-lag", setting};
    try {
      bsg::resolve_run_config(request);
      ADD_FAILURE() << "accepted";
    } catch (const bsg::ConfigError& e) {
      const std::string message = e.what();
      EXPECT_TRUE(bsg::testing::contains(message, "'" + named + "'"));
      EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
  }
  request.set_arguments = {"env_id=SafetyBallCircle-v0", "alg=td3-lag", "noise_clip=0.3"};
  EXPECT_EQ(bsg::resolve_run_config(request).config.off_policy.noise_clip, 0.3);
}

// Mean of a column over epochs [first, last).
double mean_over(const std::vector<double>& column, std::size_t first, std::size_t last) {
  return std::accumulate(column.begin() + static_cast<long>(first), column.begin() + static_cast<long>(last), 0.0) /
         static_cast<double>(last - first);
}

// A short budget per family: 10 epochs of 2000 steps on SafetyBallCircle-v0, seed 1, 64x64 nets,
// random actions for the first 2000 steps (the first epoch: the random policy's return), then one
// gradient step per 2 environment steps. TD3-Lag is the fragile one on this budget: at one step per
// 4 environment steps seed 1 stays near the random return, and at this ratio seed 2 does (both
// learn over the 300 000 steps of docs/algorithms.md#measured-off-policy).
TEST(OffPolicyLearning, EachFamilyLearnsBallCircleOnAShortBudget) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "three training runs are too slow under the sanitizers; the updates run under them above";
#endif
  constexpr int kEpochs = 10;
  for (const char* alg : {"sac-lag", "td3-lag", "ddpg-lag"}) {
    SCOPED_TRACE(alg);
    bsg::RunConfigRequest request;
    request.configs_dir = fs::path(BSG_SOURCE_DIR) / "configs";
    request.set_arguments = {"env_id=SafetyBallCircle-v0", std::string("alg=") + alg, "seed=1",
                             "epochs=" + std::to_string(kEpochs), "steps_per_epoch=2000", "eval_episodes=0",
                             "hidden_sizes=[64, 64]", "num_envs=1", "start_steps=2000", "update_every=20",
                             "updates_per_step=0.5", "buffer_size=100000"};
    if (std::string(alg) == "sac-lag") {
      // FSRL's slow multiplier, which this test was written with. With sac-lag.yaml's K_I 0.05 per
      // epoch the last 3 epochs' return was 25.9 at a cost of 18.5: the limit binds this early.
      request.set_arguments.insert(request.set_arguments.end(), {"multiplier_schedule=update_round", "pid_ki=0.0005"});
    }
    const bsg::RunConfig config = bsg::resolve_run_config(request).config;
    const TemporaryDirectory directory;
    bsg::algos::OffPolicyTrainer trainer(config, bsg::algos::RunDirectory(directory.path() / "run"),
                                         bsg::MpiContext::single_process(), {});
    ASSERT_TRUE(trainer.run().finished);
    auto progress = bsg::testing::read_csv_columns(directory.path() / "run" / "progress.csv");
    const std::vector<double>& returns = progress["episode_return_mean"];
    const std::vector<double>& costs = progress["episode_cost_mean"];
    const double random_return = returns.front();  // the first epoch acts uniformly at random
    const double last_return = mean_over(returns, kEpochs - 3, kEpochs);
    std::printf("  %s: random policy's return %.1f, last 3 epochs %.1f, cost %.1f\n", alg, random_return, last_return,
                mean_over(costs, kEpochs - 3, kEpochs));
    EXPECT_GT(last_return, random_return + 50.0);
  }
}

}  // namespace off_policy_trainer_test
}  // namespace
