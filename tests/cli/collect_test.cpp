// `bsg collect` end to end: a checkpoint's policy and the random policy into
// one file; one-line errors with exit 1 for a checkpoint of another
// environment, an unknown environment and bad counts, and no file (nor
// temporary) left behind by a refused collection.
#include <gtest/gtest.h>

#include <filesystem>
#include <memory>
#include <string>

#include "../test_support.h"
#include "algos/off_policy/make_off_policy_learner.h"
#include "algos/off_policy/off_policy_learner.h"
#include "algos/offline/dataset_file.h"
#include "algos/training/off_policy_checkpoint.h"
#include "common/run_config_yaml.h"
#include "envs/env.h"
#include "run_bsg.h"

namespace fs = std::filesystem;
using bsg::testing::run_bsg;
using bsg::testing::TemporaryDirectory;
using bsg::testing::write_text_file;

namespace {

using bsg::testing::kConfigsOption;

// One epoch of 1000 steps of TRPO-L on `env_id`.
std::string train_tiny_run(const TemporaryDirectory& dir, const std::string& env_id) {
  const fs::path file = dir.path() / (env_id + ".yaml");
  write_text_file(file, "env_id: " + env_id +
                            "\nalg: lag-trpo\nseed: 1\nepochs: 1\nsteps_per_epoch: 1000\neval_episodes: 1\n");
  const std::string out = (dir.path() / env_id).string();
  const auto trained = run_bsg("train " + file.string() + kConfigsOption + " --quiet --out " + out);
  EXPECT_EQ(trained.exit_code, 0) << trained.output;
  return out;
}

// The one line of an error, without the program's prefix.
void expect_one_line_error(const bsg::testing::ProgramResult& result, const std::string& part) {
  EXPECT_EQ(result.exit_code, 1) << result.output;
  EXPECT_NE(result.output.find(part), std::string::npos) << result.output;
  EXPECT_EQ(std::count(result.output.begin(), result.output.end(), '\n'), 1) << result.output;
}

bool only_entries(const fs::path& dir, std::size_t n) {
  return static_cast<std::size_t>(std::distance(fs::directory_iterator(dir), fs::directory_iterator())) == n;
}

TEST(Collect, MixOfACheckpointAndTheRandomPolicy) {
  TemporaryDirectory dir("collect");
  const std::string run = train_tiny_run(dir, "SafetyBallRun-v0");
  const std::string file = (dir.path() / "mix.hdf5").string();
  const auto result = run_bsg("collect --out " + file + " --policy " + run + "=3 --policy random --episodes 4 --seed 2");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const bsg::algos::OfflineDataset d = bsg::algos::read_dataset_file(file);
  EXPECT_EQ(d.text_attributes.at("env_id"), "SafetyBallRun-v0");
  EXPECT_EQ(d.number_attributes.at("episodes"), 4.0);
  // The checkpoint's three episodes first, then the random policy's one.
  const std::string& policies = d.text_attributes.at("policies");
  EXPECT_NE(policies.find("checkpoint " + run), std::string::npos) << policies;
  EXPECT_NE(policies.find("3 episodes"), std::string::npos) << policies;
  EXPECT_NE(policies.find("random: share 1.000000, 1 episodes"), std::string::npos) << policies;
  EXPECT_EQ(d.text_attributes.at("bsg_version"), BSG_VERSION_STRING);

  // A checkpoint of SafetyBallRun-v0 cannot collect on SafetyBallCircle-v0.
  const auto other = run_bsg("collect --out " + (dir.path() / "x.hdf5").string() +
                             " --env SafetyBallCircle-v0 --policy " + run + " --episodes 1");
  expect_one_line_error(other, "was trained on SafetyBallRun-v0, not on the collection's SafetyBallCircle-v0");
  EXPECT_FALSE(fs::exists(dir.path() / "x.hdf5"));
}

// An off-policy run's checkpoint collects too: with mean actions every stored
// action is the deterministic actor tanh(mu(s)) of the stored observation,
// computed here from the checkpoint's actor network directly.
TEST(Collect, AnOffPolicyCheckpointActsWithItsDeterministicActor) {
  TemporaryDirectory dir("collect");
  const fs::path config_file = dir.path() / "sac.yaml";
  write_text_file(config_file,
                  "env_id: SafetyBallCircle-v0\nalg: sac-lag\nseed: 1\nepochs: 1\nsteps_per_epoch: 400\n"
                  "num_envs: 2\nstart_steps: 200\nupdate_every: 50\nbatch_size: 32\nbuffer_size: 1000\n"
                  "hidden_sizes: [16, 16]\neval_episodes: 1\n");
  const std::string run = (dir.path() / "sac").string();
  const auto trained = run_bsg("train " + config_file.string() + kConfigsOption + " --quiet --out " + run);
  ASSERT_EQ(trained.exit_code, 0) << trained.output;
  const std::string file = (dir.path() / "sac.hdf5").string();
  const auto result = run_bsg("collect --out " + file + " --policy " + run + " --actions mean --episodes 1 --seed 3");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const bsg::algos::OfflineDataset d = bsg::algos::read_dataset_file(file);
  ASSERT_GT(d.size(), 0u);

  const bsg::RunConfig config =
      bsg::load_resolved_run_config(fs::path(run) / "config.yaml", bsg::envs::registered_ids());
  bsg::Rng unused(0);
  const std::unique_ptr<bsg::algos::OffPolicyLearner> owned_learner =
      bsg::algos::make_off_policy_learner(config, d.observation_dim, d.action_dim, 1, unused);
  bsg::algos::OffPolicyLearner& learner = *owned_learner;
  bsg::algos::load_off_policy_checkpoint(fs::path(run) / "checkpoint.bin", config, learner);
  double largest_error = 0.0;
  for (std::size_t t = 0; t < d.size(); ++t) {
    Eigen::VectorXd observation(d.observation_dim);
    for (int j = 0; j < d.observation_dim; ++j) observation(j) = d.observations[t * d.observation_dim + j];
    // The stored observation is float32: the actor sees the rounded value here, so allow float32's error.
    const Eigen::VectorXd outputs = learner.actor().forward(observation);
    for (int j = 0; j < d.action_dim; ++j) {
      largest_error = std::max(largest_error, std::abs(std::tanh(outputs(j)) - d.actions[t * d.action_dim + j]));
    }
  }
  EXPECT_LT(largest_error, 1e-4);
  EXPECT_NE(d.text_attributes.at("policies").find("deterministic actions"), std::string::npos)
      << d.text_attributes.at("policies");
}

TEST(Collect, BadInputIsOneLine) {
  TemporaryDirectory dir("collect");
  const std::string out = " --out " + (dir.path() / "x.hdf5").string();
  expect_one_line_error(run_bsg("collect" + out + " --env SafetyBallNowhere-v0 --policy random --episodes 1"),
                        "SafetyBallNowhere-v0");
  expect_one_line_error(run_bsg("collect" + out + " --env SafetyBallCircle-v0 --policy random --episodes 0"),
                        "--episodes must be at least 1, got 0");
  expect_one_line_error(run_bsg("collect" + out + " --env SafetyBallCircle-v0 --policy random --transitions -5"),
                        "--transitions must be at least 1, got -5");
  expect_one_line_error(
      run_bsg("collect" + out + " --env SafetyBallCircle-v0 --policy random --episodes 1 --transitions 9"),
      "exactly one of --episodes N and --transitions N");
  expect_one_line_error(run_bsg("collect" + out + " --env SafetyBallCircle-v0 --policy random=0 --episodes 1"),
                        "the share after '=' must be a positive number");
  expect_one_line_error(run_bsg("collect" + out + " --policy random --episodes 1"), "name the environment with --env");
  expect_one_line_error(run_bsg("collect" + out + " --env SafetyBallCircle-v0 --policy " +
                                (dir.path() / "no_run").string() + " --episodes 1"),
                        "no_run");
  EXPECT_TRUE(only_entries(dir.path(), 0));
}

TEST(Collect, TheSameCommandWritesTheSameBytes) {
  TemporaryDirectory dir("collect");
  const std::string args = " --env SafetyBallReach-v0 --policy random --episodes 2 --seed 4";
  ASSERT_EQ(run_bsg("collect --out " + (dir.path() / "a.hdf5").string() + args).exit_code, 0);
  ASSERT_EQ(run_bsg("collect --out " + (dir.path() / "b.hdf5").string() + args).exit_code, 0);
  const std::string a = bsg::testing::read_text_file(dir.path() / "a.hdf5");
  EXPECT_GT(a.size(), 1000u);
  EXPECT_TRUE(a == bsg::testing::read_text_file(dir.path() / "b.hdf5"));
}

// Checkpoints of one environment with other constraints cannot share a file:
// its costs would mean different things. One with the same terms at another
// limit can (a grid over cost limits); the file then holds one column per
// constraint and the costs summed, as the two-constraint run recorded them.
TEST(Collect, CheckpointsMustHaveTheSameConstraints) {
  TemporaryDirectory dir("collect");
  const std::string whole = train_tiny_run(dir, "SafetyBallGather-v0");
  const auto train_two = [&](const std::string& name, const std::string& bomb_limit) {
    const fs::path file = dir.path() / (name + ".yaml");
    write_text_file(file, "env_id: SafetyBallGather-v0\nalg: lag-trpo\nseed: 1\nepochs: 1\nsteps_per_epoch: 1000\n"
                          "eval_episodes: 1\nconstraints:\n  - terms: [cost_gathered_bombs]\n    limit: " +
                              bomb_limit + "\n  - terms: [cost_out_of_range]\n    limit: 0.1\n");
    const std::string out = (dir.path() / name).string();
    const auto trained = run_bsg("train " + file.string() + kConfigsOption + " --quiet --out " + out);
    EXPECT_EQ(trained.exit_code, 0) << trained.output;
    return out;
  };
  const std::string two = train_two("two", "0.2");
  const std::string two_looser = train_two("two_looser", "3");
  const auto refused = run_bsg("collect --out " + (dir.path() / "x.hdf5").string() + " --policy " + two +
                               " --policy " + whole + " --episodes 2");
  expect_one_line_error(refused, "checkpoint " + whole + " has other constraints than the first one");
  EXPECT_FALSE(fs::exists(dir.path() / "x.hdf5"));

  const std::string file = (dir.path() / "two.hdf5").string();
  const auto made = run_bsg("collect --out " + file + " --policy " + two + " --policy " + two_looser + " --episodes 2");
  ASSERT_EQ(made.exit_code, 0) << made.output;
  const bsg::algos::OfflineDataset d = bsg::algos::read_dataset_file(file);
  ASSERT_EQ(d.constraint_costs.size(), 2 * d.size());
  for (std::size_t t = 0; t < d.size(); ++t) {
    ASSERT_FLOAT_EQ(d.costs[t], d.constraint_costs[2 * t] + d.constraint_costs[2 * t + 1]) << t;
  }
  EXPECT_EQ(d.constraint_names, (std::vector<std::string>{"cost_gathered_bombs", "cost_out_of_range"}));
  // Several constraints: the stored limit is the environment's own (Gather's 0.2), not one constraint's.
  EXPECT_EQ(d.number_attributes.at("cost_limit"), 0.2);
}

TEST(Collect, RefusesToReplaceAFileWithoutForce) {
  TemporaryDirectory dir("collect");
  const std::string file = (dir.path() / "d.hdf5").string();
  const std::string args = "collect --out " + file + " --env SafetyBallCircle-v0 --policy random --transitions 10";
  ASSERT_EQ(run_bsg(args).exit_code, 0);
  expect_one_line_error(run_bsg(args), "exists (--force replaces it)");
  EXPECT_EQ(run_bsg(args + " --force").exit_code, 0);
  EXPECT_EQ(bsg::algos::read_dataset_file(file).size(), 10u);
  EXPECT_TRUE(only_entries(dir.path(), 1));
}

}  // namespace

namespace {

TEST(DatasetCommand, InfoCountsEpisodesAndDrawsThePlot) {
  TemporaryDirectory dir("dataset_info");
  const std::string file = (dir.path() / "d.hdf5").string();
  // 600 transitions of 250-step episodes: two complete episodes and a cut third (rows 500..599).
  ASSERT_EQ(run_bsg("collect --out " + file + " --env SafetyBallCircle-v0 --policy random --transitions 600").exit_code,
            0);
  const std::string png = (dir.path() / "scatter.png").string();
  const auto info = run_bsg("dataset info " + file + " --plot " + png);
  ASSERT_EQ(info.exit_code, 0) << info.output;
  EXPECT_NE(info.output.find("transitions 600, complete episodes 3 (0 ended by the environment)"), std::string::npos)
      << info.output;
  EXPECT_NE(info.output.find("policies:\n  random: share 1.000000, 3 episodes, 600 transitions\n"), std::string::npos)
      << info.output;
  const std::string bytes = bsg::testing::read_text_file(png);
  ASSERT_GE(bytes.size(), 8u);
  EXPECT_EQ(bytes.substr(1, 3), "PNG");
}

TEST(DatasetCommand, InfoIndentsEveryPolicyLine) {
  TemporaryDirectory dir("dataset_info");
  const std::string file = (dir.path() / "d.hdf5").string();
  ASSERT_EQ(
      run_bsg("collect --out " + file + " --env SafetyBallCircle-v0 --policy random --policy random=3 --transitions 8")
          .exit_code,
      0);
  const auto info = run_bsg("dataset info " + file);
  ASSERT_EQ(info.exit_code, 0) << info.output;
  // Shares 1:3 of 8 transitions: 2 and 6, each one cut episode.
  EXPECT_NE(info.output.find("policies:\n  random: share 1.000000, 1 episodes, 2 transitions\n"
                             "  random: share 3.000000, 1 episodes, 6 transitions\n"),
            std::string::npos)
      << info.output;
}

TEST(DatasetCommand, BadInputIsOneLine) {
  TemporaryDirectory dir("dataset_info");
  write_text_file(dir.path() / "x.hdf5", "not hdf5\n");
  expect_one_line_error(run_bsg("dataset info " + (dir.path() / "x.hdf5").string()), "not an HDF5 file");
  expect_one_line_error(run_bsg("dataset bc " + (dir.path() / "x.hdf5").string()), "not an HDF5 file");
  // A hand-made file of one episode that costs 1 at each of its 2 steps:
  // BC-Safe at kappa = 1 has nothing to learn from.
  bsg::algos::OfflineDataset d;
  d.observation_dim = 1;
  d.action_dim = 1;
  d.observations = d.next_observations = d.actions = {0, 0};
  d.rewards = {1, 1};
  d.costs = {1, 1};
  d.terminals = {0, 0};
  d.timeouts = {0, 1};
  d.text_attributes["env_description"] = "agent: Ball\ntask: Run\n";
  d.number_attributes = {{"cost_limit", 1}, {"min_episode_reward", 0}, {"max_episode_reward", 2}};
  const std::string file = (dir.path() / "d.hdf5").string();
  bsg::algos::write_dataset_file(file, d);
  expect_one_line_error(run_bsg("dataset bc " + file + " --variant safe --updates 1"),
                        "BC-Safe finds no episode with cost return <= 1");
  d.number_attributes.erase("max_episode_reward");
  bsg::algos::write_dataset_file(file, d);
  expect_one_line_error(run_bsg("dataset bc " + file + " --updates 1"), "no attribute max_episode_reward");
}

}  // namespace
