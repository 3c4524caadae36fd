// The offline family (algos/training/offline_family.h) in the run skeleton, on small hand-made
// datasets for SafetyBallCircle-v0 whose best behaviour-cloning policy is known: every action the
// same constant c (the policy learns c everywhere, and its loss falls); safe episodes acting +0.5
// and unsafe ones -0.5 on the same observations (BC-Safe learns +0.5, BC-All their row-weighted
// mean 0). The normalised columns follow DSRL's formula from the file's constants; a run stopped
// after one epoch and resumed writes the uninterrupted run's files; `bsg eval` (evaluate_run_directory
// through load_policy) reproduces evaluation.json; and the errors name what is wrong.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "../../test_support.h"
#include "algos/offline/dataset_file.h"
#include "algos/training/load_policy.h"
#include "algos/training/offline_trainer.h"
#include "algos/training/run_evaluation.h"
#include "common/config_error.h"
#include "common/run_config_checks.h"
#include "common/run_config_resolve.h"
#include "envs/env.h"

namespace fs = std::filesystem;
using bsg::testing::TemporaryDirectory;

namespace bsg::algos {
namespace {

constexpr const char* kEnv = "SafetyBallCircle-v0";

// Episodes of 10 steps on observations uniform in [-1, 1]: episode e acts action_of(e) in every
// dimension with cost cost_of(e) per step.
template <typename Action, typename Cost>
OfflineDataset make_dataset(int episodes, Action action_of, Cost cost_of, const std::string& env_id = kEnv) {
  const envs::EnvSpec spec = envs::make(kEnv)->spec();
  OfflineDataset d;
  d.observation_dim = spec.observation_dim;
  d.action_dim = spec.action_dim;
  Rng rng(11);
  for (int e = 0; e < episodes; ++e) {
    for (int t = 0; t < 10; ++t) {
      for (int k = 0; k < d.observation_dim; ++k) {
        d.observations.push_back(static_cast<float>(uniform(rng, -1.0, 1.0)));
        d.next_observations.push_back(0.0f);
      }
      for (int k = 0; k < d.action_dim; ++k) d.actions.push_back(static_cast<float>(action_of(e)));
      d.rewards.push_back(static_cast<float>(e % 3));
      d.costs.push_back(static_cast<float>(cost_of(e)));
      d.terminals.push_back(0.0f);
      d.timeouts.push_back(t == 9 ? 1.0f : 0.0f);
    }
  }
  d.text_attributes["env_id"] = env_id;
  d.number_attributes["min_episode_reward"] = 0.0;
  d.number_attributes["max_episode_reward"] = 400.0;
  return d;
}

RunConfig offline_config(const std::string& alg, const fs::path& dataset, std::vector<std::string> more = {}) {
  RunConfigRequest request;
  request.configs_dir = fs::path(BSG_SOURCE_DIR) / "configs";
  request.set_arguments = {"env_id=" + std::string(kEnv), "alg=" + alg, "dataset=" + dataset.string(),
                           "epochs=3", "updates_per_epoch=150", "batch_size=32", "hidden_sizes=[16]",
                           "eval_episodes=2", "max_ep_len=30", "eval_every=1", "save_freq=2", "cost_limit=5",
                           "actor_lr=0.01"};
  request.set_arguments.insert(request.set_arguments.end(), more.begin(), more.end());
  return resolve_run_config(request).config;
}

std::string without_times(const fs::path& path) {
  std::string text;
  for (const auto& row : bsg::testing::read_csv_rows(path)) {
    for (std::size_t c = 0; c + 2 < row.size(); ++c) text += row[c] + ",";  // time_update_s, time_s last
    text += "\n";
  }
  return text;
}

std::vector<double> act_everywhere(ActingPolicy& policy, int samples) {
  std::vector<double> actions;
  std::vector<double> observation(static_cast<std::size_t>(policy.observation_size()));
  std::vector<double> action(static_cast<std::size_t>(policy.action_size()));
  Rng rng(5), unused(0);
  for (int i = 0; i < samples; ++i) {
    for (double& x : observation) x = uniform(rng, -0.9, 0.9);
    policy.act(observation, ActionMode::mean, unused, action);
    actions.insert(actions.end(), action.begin(), action.end());
  }
  return actions;
}

TEST(OfflineTrainer, ClonesAConstantDemonstratorAndLogsDsrlsScores) {
  const TemporaryDirectory dir("offline");
  const fs::path file = dir.path() / "constant.h5";
  write_dataset_file(file, make_dataset(20, [](int) { return 0.25; }, [](int) { return 0.0; }));
  const RunConfig config = offline_config("bc-all", file);
  const RunDirectory run(dir.path() / "run");
  OfflineTrainer trainer(config, run, MpiContext::single_process(), {});
  const TrainingOutcome outcome = trainer.run();
  ASSERT_TRUE(outcome.finished);

  OfflineFamily& family = const_cast<OfflineFamily&>(trainer.offline());
  for (double a : act_everywhere(const_cast<OfflineAlgorithm&>(family.algorithm()).acting(), 50)) {
    EXPECT_NEAR(a, 0.25, 0.02);
  }
  const auto columns = bsg::testing::read_csv_columns(run.progress());
  ASSERT_EQ(columns.at("epoch").size(), 3u);
  EXPECT_EQ(columns.at("updates"), (std::vector<double>{150, 300, 450}));
  EXPECT_LT(columns.at("loss")[2], columns.at("loss")[0] / 10);
  for (std::size_t k = 0; k < 3; ++k) {
    // DSRL: (R - R_min) / (R_max - R_min); (C + 0) / kappa for kappa = 5 > 0.
    EXPECT_NEAR(columns.at("normalized_reward")[k], (columns.at("eval_return")[k] - 0.0) / 400.0, 1e-9);
    EXPECT_NEAR(columns.at("normalized_cost")[k], columns.at("eval_cost")[k] / 5.0, 1e-9);
    EXPECT_EQ(columns.at("eval_length")[k], 30.0);
  }
  // The last epoch's evaluation is the final one (the same seeds).
  EXPECT_NEAR(outcome.evaluation->mean_return, columns.at("eval_return")[2], 1e-6 * (1 + std::abs(columns.at("eval_return")[2])));
}

TEST(OfflineTrainer, BcSafeClonesTheSafeEpisodesAndBcAllTheirMean) {
  const TemporaryDirectory dir("offline");
  const fs::path file = dir.path() / "two.h5";
  // Even episodes safe (cost 0) acting +0.5, odd ones unsafe (10 per step) acting -0.5.
  write_dataset_file(file, make_dataset(20, [](int e) { return e % 2 == 0 ? 0.5 : -0.5; },
                                        [](int e) { return e % 2 == 0 ? 0.0 : 10.0; }));
  for (const std::string alg : {"bc-safe", "bc-all"}) {
    SCOPED_TRACE(alg);
    const RunConfig config = offline_config(alg, file, {"eval_episodes=0", "epochs=2", "updates_per_epoch=300"});
    OfflineTrainer trainer(config, RunDirectory(dir.path() / alg), MpiContext::single_process(), {});
    ASSERT_TRUE(trainer.run().finished);
    EXPECT_EQ(trainer.offline().training_rows().rows.size(), alg == "bc-safe" ? 100u : 200u);
    double mean = 0.0;
    const std::vector<double> actions =
        act_everywhere(const_cast<OfflineAlgorithm&>(trainer.offline().algorithm()).acting(), 100);
    for (double a : actions) mean += a / static_cast<double>(actions.size());
    EXPECT_NEAR(mean, alg == "bc-safe" ? 0.5 : 0.0, 0.1);
  }
}

TEST(OfflineTrainer, AResumedRunWritesTheUninterruptedRunsFiles) {
  const TemporaryDirectory dir("offline");
  const fs::path file = dir.path() / "data.h5";
  write_dataset_file(file, make_dataset(12, [](int e) { return 0.1 * (e % 4) - 0.1; }, [](int e) { return e % 3; }));
  // CPQ draws noise from the batch stream too, and keeps critics, targets, a VAE and alpha.
  // BCQ-Lag too, with its target actor and its controller's state; COptiDICE with its duals.
  for (const std::string alg : {"bc-safe", "cpq", "bcq-lag", "coptidice"}) {
    SCOPED_TRACE(alg);
    const fs::path root = dir.path() / alg;
    const std::vector<std::string> small = alg == "cpq"       ? std::vector<std::string>{"vae_hidden_size=8", "cpq_sampled_actions=2"}
                                           : alg == "bcq-lag" ? std::vector<std::string>{"vae_hidden_size=8", "bcq_sampled_actions=2",
                                                                                         "updates_per_epoch=20"}
                                                              : std::vector<std::string>{};
    const RunConfig config = offline_config(alg, file, small);
    OfflineTrainer whole(config, RunDirectory(root / "whole"), MpiContext::single_process(), {});
    ASSERT_TRUE(whole.run().finished);
    TrainerOptions stop;
    stop.stop_after_epochs = 1;
    {
      OfflineTrainer first(config, RunDirectory(root / "split"), MpiContext::single_process(), stop);
      EXPECT_EQ(first.run().epochs_completed, 1);
    }
    TrainerOptions resume;
    resume.resume = true;
    OfflineTrainer second(config, RunDirectory(root / "split"), MpiContext::single_process(), resume);
    ASSERT_EQ(second.epochs_completed(), 1);
    ASSERT_TRUE(second.run().finished);
    EXPECT_EQ(without_times(root / "split" / "progress.csv"), without_times(root / "whole" / "progress.csv"));
    for (const char* name : {"evaluation.json", "returns.csv", "costs.csv"}) {
      EXPECT_EQ(bsg::testing::read_text_file(root / "split" / name), bsg::testing::read_text_file(root / "whole" / name))
          << name;
    }
  }
}

TEST(OfflineTrainer, BsgEvalLoadsTheRunsPolicy) {
  const TemporaryDirectory dir("offline");
  const fs::path file = dir.path() / "data.h5";
  write_dataset_file(file, make_dataset(10, [](int e) { return 0.2 * (e % 3); }, [](int) { return 0.0; }));
  const RunDirectory run(dir.path() / "run");
  OfflineTrainer trainer(offline_config("bc-all", file, {"epochs=2"}), run, MpiContext::single_process(), {});
  const TrainingOutcome outcome = trainer.run();
  const std::unique_ptr<LoadedPolicy> loaded = load_policy(run);
  EXPECT_EQ(loaded->epochs_completed(), 2);
  EXPECT_EQ(loaded->config().alg, Algorithm::bc_all);
  EXPECT_EQ(act_everywhere(*loaded, 20),
            act_everywhere(const_cast<OfflineAlgorithm&>(trainer.offline().algorithm()).acting(), 20));
  const RunEvaluation again = evaluate_run_directory(run, std::nullopt, MpiContext::single_process());
  EXPECT_EQ(again.summary.mean_return, outcome.evaluation->mean_return);
  EXPECT_EQ(again.summary.mean_cost, outcome.evaluation->mean_cost);
}

TEST(OfflineTrainer, ErrorsNameWhatIsWrong) {
  const TemporaryDirectory dir("offline");
  RunConfigRequest request;
  request.configs_dir = fs::path(BSG_SOURCE_DIR) / "configs";
  request.set_arguments = {"env_id=" + std::string(kEnv), "alg=bc-all"};
  try {
    resolve_run_config(request);
    FAIL() << "no dataset";
  } catch (const ConfigError& e) {
    EXPECT_TRUE(bsg::testing::contains(e.what(), "set 'dataset: FILE'"));
  }
  // A key of another family, and the offline keys on another family.
  request.set_arguments = {"env_id=" + std::string(kEnv), "alg=bc-all", "dataset=x.h5", "gamma=0.9"};
  EXPECT_THROW(resolve_run_config(request), ConfigError);
  request.set_arguments = {"env_id=" + std::string(kEnv), "alg=sac", "dataset=x.h5"};
  EXPECT_THROW(resolve_run_config(request), ConfigError);
  // CPQ's and BCQ-Lag's keys: refused on another algorithm, and out of their range, each with one line naming the key.
  for (const std::vector<std::string>& bad :
       {std::vector<std::string>{"alg=bc-all", "cpq_sampled_actions=3"}, {"alg=cpq", "cpq_sampled_actions=0"},
        {"alg=cpq", "vae_kl_weight=-1"}, {"alg=cpq", "reward_scale=0"}, {"alg=cpq", "bcq_phi=0.1"},
        {"alg=bcq-lag", "bcq_lambda=1.5"}, {"alg=bcq-lag", "bcq_sampled_actions=0"}, {"alg=bcq-lag", "bcq_pid_ki=-1"},
        {"alg=bcq-lag", "cpq_qc_scalar=2"}, {"alg=coptidice", "coptidice_f_divergence=js"},
        {"alg=coptidice", "coptidice_alpha=0"}, {"alg=coptidice", "polyak=0.1"}, {"alg=bcq-lag", "coptidice_alpha=1"}}) {
    request.set_arguments = {"env_id=" + std::string(kEnv), "dataset=x.h5"};
    request.set_arguments.insert(request.set_arguments.end(), bad.begin(), bad.end());
    try {
      resolve_run_config(request);
      FAIL() << bad[1];
    } catch (const ConfigError& e) {
      const std::string key = bad[1].substr(0, bad[1].find('='));
      EXPECT_TRUE(bsg::testing::contains(e.what(), key)) << e.what();
      EXPECT_FALSE(bsg::testing::contains(e.what(), "\n")) << e.what();
    }
  }

  const RunConfig missing = offline_config("bc-all", dir.path() / "nowhere.h5");
  try {
    OfflineTrainer trainer(missing, RunDirectory(dir.path() / "a"), MpiContext::single_process(), {});
    FAIL() << "no file";
  } catch (const std::exception& e) {
    EXPECT_TRUE(bsg::testing::contains(e.what(), "nowhere.h5"));
  }

  const fs::path car = dir.path() / "car.h5";
  write_dataset_file(car, make_dataset(4, [](int) { return 0.0; }, [](int) { return 0.0; }, "SafetyCarCircle-v0"));
  try {
    OfflineTrainer trainer(offline_config("bc-all", car), RunDirectory(dir.path() / "b"), MpiContext::single_process(), {});
    FAIL() << "another environment";
  } catch (const std::exception& e) {
    EXPECT_TRUE(bsg::testing::contains(e.what(), "collected on SafetyCarCircle-v0, but the run's env_id is " +
                                                     std::string(kEnv)));
  }

  const fs::path unsafe = dir.path() / "unsafe.h5";
  write_dataset_file(unsafe, make_dataset(4, [](int) { return 0.0; }, [](int) { return 1.0; }));
  try {
    OfflineTrainer trainer(offline_config("bc-safe", unsafe), RunDirectory(dir.path() / "c"),
                           MpiContext::single_process(), {});
    FAIL() << "no safe episode";
  } catch (const std::exception& e) {
    EXPECT_TRUE(bsg::testing::contains(e.what(), "BC-Safe finds no episode with cost return <= 5.000000"));
  }

  try {
    check_run_config_for_ranks(offline_config("bc-all", unsafe), 2);
    FAIL() << "two ranks";
  } catch (const ConfigError& e) {
    EXPECT_TRUE(bsg::testing::contains(e.what(), "trains on one rank, not 2"));
  }
}

}  // namespace
}  // namespace bsg::algos
