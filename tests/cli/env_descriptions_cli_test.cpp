// Environment descriptions on the command line: `bsg envs --describe`, the
// `--set` overrides of `bsg rollout`, a custom environment trained, resumed and
// evaluated from its run directory, and one-line errors for bad input.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "../test_support.h"
#include "progress_rows.h"
#include "run_bsg.h"

namespace fs = std::filesystem;
using bsg::testing::progress_without_timings;
using bsg::testing::read_text_file;
using bsg::testing::run_bsg;
using bsg::testing::TemporaryDirectory;
using bsg::testing::write_text_file;

namespace {

using bsg::testing::kConfigsOption;

using bsg::testing::contains;

TEST(EnvsDescribe, PrintsTheResolvedDescriptionWithItsSizes) {
  const auto result = run_bsg("envs --describe SafetyAntGather-v0 --set bombs=16");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_TRUE(contains(result.output, "# SafetyAntGather-v0: observation 65, action 8\n")) << result.output;
  EXPECT_TRUE(contains(result.output, "\nbombs: 16  #")) << result.output;
  EXPECT_TRUE(contains(result.output, "\napples: 8  #")) << result.output;
  EXPECT_TRUE(contains(result.output, "\nmax_episode_steps: 1000  #")) << result.output;
  EXPECT_FALSE(contains(result.output, "\nzones:")) << "a Reach key on Gather";
}

TEST(Rollout, AnOverrideThatRepeatsTheDefaultPlaysTheRecordedEpisodes) {
  const auto result = run_bsg("rollout --env SafetyBallGather-v0 --policy random --seed 7 --episodes 2 --json "
                              "--set bombs=8 --set gather_spacing=2");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const auto out = nlohmann::json::parse(result.output);
  const auto recorded = nlohmann::json::parse(
      read_text_file(fs::path(BSG_TEST_DATA_DIR) / "rollouts" / "SafetyBallGather-v0_random_seed7.json"));
  EXPECT_EQ(out.at("episodes"), recorded.at("episodes"));
  EXPECT_EQ(out.at("overrides").at("bombs"), "8");
}

TEST(Rollout, ACustomEpisodeLengthIsPlayed) {
  const auto result = run_bsg("rollout --env SafetyBallCircle-v0 --policy zero --json --set max_episode_steps=37");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_EQ(nlohmann::json::parse(result.output).at("episodes").at(0).at("length"), 37);
}

TEST(BadOverrides, AreOneLineErrorsNamingKeyAndValue) {
  for (const auto& [command, part] : std::initializer_list<std::pair<std::string, std::string>>{
           {"rollout --env SafetyBallGather-v0 --set bomb=3", "bomb=3: unknown parameter (did you mean bombs?)"},
           {"envs --describe SafetyBallGather-v0 --set bombs=-2", "bombs=-2: must be >= 0"},
           {"bench --env SafetyBallCircle-v0 --steps 10 --set bombs=2", "bombs=2: the Circle task has no such"},
           {"envs --describe SafetyBallGather-v0 --set agent=Robot", "agent=Robot: unknown agent"},
           {"rollout --env SafetyBallGather-v0 --set apples=300", "apples + bombs=308: cannot place"},
           {"rollout --env SafetyBallGather-v0 --set bombs", "--set bombs: expected key=value"}}) {
    SCOPED_TRACE(command);
    const auto result = run_bsg(command);
    EXPECT_EQ(result.exit_code, 1) << result.output;
    EXPECT_TRUE(contains(result.output, part)) << result.output;
    EXPECT_EQ(result.output.find('\n'), result.output.size() - 1) << result.output;
  }
}

std::string run_file(const TemporaryDirectory& dir, const std::string& env_lines) {
  const fs::path path = dir.path() / "run.yaml";
  write_text_file(path, "alg: lag-trpo\nseed: 3\nepochs: 4\nsteps_per_epoch: 500\nsave_freq: 1\n"
                        "eval_episodes: 2\ncost_limit: 1\n" + env_lines);
  return path.string();
}

TEST(CustomRun, ResumeAndEvalRebuildTheSameEnvironment) {
  const TemporaryDirectory dir;
  // 8-bin sensors: observation 7 + 16 = 23 instead of 39, so a run that
  // rebuilt the standard environment could not load its own checkpoint.
  const std::string file = run_file(
      dir, "env_id: SafetyBallGather-v0\nenv: {bombs: 12, gather_sensor_bins: 8, max_episode_steps: 100}\n");
  const auto whole = run_bsg("train " + file + kConfigsOption + " --quiet --out " + dir.str("whole"));
  ASSERT_EQ(whole.exit_code, 0) << whole.output;
  const std::string config = read_text_file(dir.path() / "whole" / "config.yaml");
  EXPECT_TRUE(contains(config, "\nenv: {name: SafetyBallGather-v0, agent: Ball, task: Gather,")) << config;
  EXPECT_TRUE(contains(config, "bombs: 12, gather_detection_distance: 1.0")) << config;
  EXPECT_TRUE(contains(config, "gather_sensor_bins: 8,")) << config;
  EXPECT_TRUE(contains(config, "\nmax_ep_len: 100  #")) << "max_ep_len follows max_episode_steps: " << config;

  const auto first = run_bsg("train " + file + kConfigsOption + " --quiet --stop-after 2 --out " + dir.str("split"));
  ASSERT_EQ(first.exit_code, 0) << first.output;
  const auto resumed = run_bsg("train --resume " + dir.str("split") + " --quiet");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_EQ(progress_without_timings(dir.path() / "split" / "progress.csv"),
            progress_without_timings(dir.path() / "whole" / "progress.csv"));
  EXPECT_EQ(read_text_file(dir.path() / "split" / "returns.csv"),
            read_text_file(dir.path() / "whole" / "returns.csv"));

  const auto eval = run_bsg("eval " + dir.str("whole") + " --episodes 2");
  ASSERT_EQ(eval.exit_code, 0) << eval.output;
}

TEST(CustomRun, AWholeDescriptionNamesItsStandardEnvironment) {
  const TemporaryDirectory dir;
  const std::string file = run_file(dir, "env: {agent: Ant, task: Gather, bombs: 16, name: AntGather16}\n");
  const auto result = run_bsg("train --print-config " + file + kConfigsOption + " --set steps_per_epoch=2000");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_TRUE(contains(result.output, "\nenv_id: SafetyAntGather-v0  #")) << result.output;
  EXPECT_TRUE(contains(result.output, "name: AntGather16, agent: Ant, task: Gather")) << result.output;
  EXPECT_TRUE(contains(result.output, "bombs: 16")) << result.output;
  EXPECT_TRUE(contains(result.output, "\nmax_ep_len: 1000  #")) << result.output;  // configs/envs of AntGather
}

TEST(CustomRun, ABadEnvBlockIsAnErrorNamingTheKey) {
  const TemporaryDirectory dir;
  const auto result =
      run_bsg("train " + run_file(dir, "env_id: SafetyBallGather-v0\nenv: {bomb: 3}\n") + kConfigsOption + " --quiet");
  EXPECT_EQ(result.exit_code, 1) << result.output;
  EXPECT_TRUE(contains(result.output, "bomb=3: unknown parameter (did you mean bombs?)")) << result.output;
}

}  // namespace
