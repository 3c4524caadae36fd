// `bsg dataset make RECIPE` end to end on a tiny recipe: the grid trained by
// the sweep machinery, one file per environment with each run's episodes and
// the random policy's; a second make after an interruption (the file gone, a
// stale temporary left) writes the same bytes as the uninterrupted one; a
// recipe with an unknown key is one line and writes nothing; every shipped
// recipe (configs/datasets/) plans.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <string>

#include "../test_support.h"
#include "algos/offline/dataset_file.h"
#include "run_bsg.h"

namespace fs = std::filesystem;
using bsg::testing::read_text_file;
using bsg::testing::run_bsg;
using bsg::testing::TemporaryDirectory;
using bsg::testing::write_text_file;

namespace {

using bsg::testing::kConfigsOption;

const char* const kTinyRecipe =
    "description: two one-epoch TRPO-L runs on the fork's BallRun\n"
    "grid:\n"
    "  envs: [SafetyBallRun-fork]\n"
    "  seeds: [0]\n"
    "  fixed: {epochs: 1, steps_per_epoch: 1000, eval_episodes: 1, max_ep_len: 250, cost_limit: 25}\n"
    "  algorithms:\n"
    "    lag-trpo:\n"
    "      axes: {cost_limit: [5, 40]}\n"
    "collect:\n"
    "  episodes_per_run: 2\n"
    "  random_episodes: 1\n"
    "  seed: 3\n";

TEST(DatasetMake, TinyRecipeAndItsResume) {
  TemporaryDirectory dir("dataset_make");
  write_text_file(dir.path() / "tiny.yaml", kTinyRecipe);
  const std::string out = (dir.path() / "out").string();
  const std::string command = "dataset make " + (dir.path() / "tiny.yaml").string() + " --out " + out + kConfigsOption;
  const auto made = run_bsg(command);
  ASSERT_EQ(made.exit_code, 0) << made.output;
  const fs::path file = dir.path() / "out" / "SafetyBallRun-fork.hdf5";
  const bsg::algos::OfflineDataset d = bsg::algos::read_dataset_file(file);
  // Two runs x 2 episodes and 1 random episode of the fork's 100 steps.
  EXPECT_EQ(d.size(), 500u);
  EXPECT_EQ(d.number_attributes.at("episodes"), 5.0);
  const std::string& policies = d.text_attributes.at("policies");
  EXPECT_NE(policies.find("lag-trpo/cost_limit=5/seed=0"), std::string::npos) << policies;
  EXPECT_NE(policies.find("lag-trpo/cost_limit=40/seed=0"), std::string::npos) << policies;
  EXPECT_NE(policies.find("random: share 1.000000, 1 episodes"), std::string::npos) << policies;
  // Named from the dataset's folder, not from where the folder happens to be.
  EXPECT_NE(policies.find("checkpoint sweep/SafetyBallRun-fork/lag-trpo/cost_limit=5/seed=0 ("), std::string::npos)
      << policies;
  EXPECT_EQ(policies.find(dir.path().string()), std::string::npos) << policies;
  const std::string uninterrupted = read_text_file(file);

  // Again: the file is kept.
  const auto again = run_bsg(command);
  ASSERT_EQ(again.exit_code, 0) << again.output;
  EXPECT_NE(again.output.find("kept"), std::string::npos) << again.output;

  // Interrupted during the collection: no file, a stale temporary. The resumed make writes the same bytes.
  fs::remove(file);
  write_text_file(file.string() + ".tmp.999999.abcdef", "half");
  fs::last_write_time(file.string() + ".tmp.999999.abcdef", fs::file_time_type::clock::now() - std::chrono::minutes(5));
  const auto resumed = run_bsg(command);
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_TRUE(read_text_file(file) == uninterrupted);
  EXPECT_FALSE(fs::exists(file.string() + ".tmp.999999.abcdef"));

  // The folder moved elsewhere and its file made again from the same checkpoints: the same bytes,
  // so that a checksum list holds wherever the datasets are rebuilt.
  const fs::path moved = dir.path() / "elsewhere" / "out";
  fs::create_directories(moved.parent_path());
  fs::rename(dir.path() / "out", moved);
  fs::remove(moved / "SafetyBallRun-fork.hdf5");
  const auto remade = run_bsg("dataset make " + (dir.path() / "tiny.yaml").string() + " --out " + moved.string() +
                              kConfigsOption);
  ASSERT_EQ(remade.exit_code, 0) << remade.output;
  EXPECT_TRUE(read_text_file(moved / "SafetyBallRun-fork.hdf5") == uninterrupted);
}

TEST(DatasetMake, UnknownKeyIsOneLineAndWritesNothing) {
  TemporaryDirectory dir("dataset_make");
  write_text_file(dir.path() / "bad.yaml", std::string(kTinyRecipe).append("colect: {seed: 1}\n"));
  const auto result =
      run_bsg("dataset make " + (dir.path() / "bad.yaml").string() + " --out " + (dir.path() / "out").string() + kConfigsOption);
  EXPECT_EQ(result.exit_code, 1) << result.output;
  EXPECT_NE(result.output.find("bad.yaml:13: unknown key 'colect' (expected description, grid, collect)"),
            std::string::npos)
      << result.output;
  EXPECT_EQ(std::count(result.output.begin(), result.output.end(), '\n'), 1) << result.output;
  EXPECT_FALSE(fs::exists(dir.path() / "out"));
  write_text_file(dir.path() / "bad.yaml",
                  std::string(kTinyRecipe).replace(std::string(kTinyRecipe).find("episodes_per_run: 2"), 19,
                                                   "episodes_per_run: 0"));
  const auto zero =
      run_bsg("dataset make " + (dir.path() / "bad.yaml").string() + " --out " + (dir.path() / "out").string() + kConfigsOption);
  EXPECT_EQ(zero.exit_code, 1) << zero.output;
  EXPECT_NE(zero.output.find("collect.episodes_per_run must be at least 1, got 0"), std::string::npos) << zero.output;
}

TEST(DatasetMake, EveryShippedRecipePlans) {
  int recipes = 0;
  for (const fs::directory_entry& entry : fs::directory_iterator(fs::path(BSG_SOURCE_DIR) / "configs" / "datasets")) {
    if (entry.path().extension() != ".yaml") continue;
    ++recipes;
    const auto planned = run_bsg("dataset make " + entry.path().string() + " --dry-run --out /nonexistent/x" + kConfigsOption);
    EXPECT_EQ(planned.exit_code, 0) << entry.path() << "\n" << planned.output;
    EXPECT_NE(planned.output.find("random episodes"), std::string::npos) << planned.output;
  }
  EXPECT_EQ(recipes, 11);  // the recipes of docs/datasets.md's table
}

}  // namespace
