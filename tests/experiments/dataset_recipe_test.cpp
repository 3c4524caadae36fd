// A dataset recipe (experiments/dataset_recipe.h): its defaults and values;
// one-line errors naming the file and the line counted by hand in the text;
// the grid file it writes, read back by the grid parser; the files it plans
// from a sweep plan built here by hand, with their policies in the sweep's
// order and their episodes summed; every shipped recipe reads.
#include "experiments/dataset_recipe.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <stdexcept>
#include <string>

#include "../test_support.h"
#include "experiments/grid_file.h"

namespace bsg::experiments {
namespace {

namespace fs = std::filesystem;

const char* const kRecipe =
    "description: two runs on BallRun\n"                 // line 1
    "grid:\n"                                            // line 2
    "  envs: [SafetyBallRun-fork, SafetyBallCircle-v0]\n"  // line 3
    "  seeds: [0]\n"                                     // line 4
    "  algorithms:\n"                                    // line 5
    "    lag-trpo:\n"                                    // line 6
    "      axes: {cost_limit: [5, 40]}\n"                // line 7
    "collect:\n"                                         // line 8
    "  episodes_per_run: 2\n"                            // line 9
    "  random_episodes: 1\n"                             // line 10
    "  actions: mean\n"                                  // line 11
    "  seed: 3\n";                                       // line 12

const char* const kGridOnly = "grid: {envs: [SafetyBallCircle-v0], seeds: [0], algorithms: {trpo: {}}}\n";

std::string error_of(const std::string& text) {
  try {
    parse_dataset_recipe(text, "r.yaml");
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(DatasetRecipe, ReadsItsValuesAndDefaults) {
  const DatasetRecipe recipe = parse_dataset_recipe(kRecipe, "r.yaml");
  EXPECT_EQ(recipe.collect.episodes_per_run, 2);
  EXPECT_EQ(recipe.collect.random_episodes, 1);
  EXPECT_EQ(recipe.collect.actions, "mean");
  EXPECT_EQ(recipe.collect.seed, 3);
  // Without collect: 10 episodes per run, no random episodes, sampled actions, seed 0 (the header's table).
  const DatasetRecipe defaults = parse_dataset_recipe(kGridOnly, "r.yaml");
  EXPECT_EQ(defaults.collect.episodes_per_run, 10);
  EXPECT_EQ(defaults.collect.random_episodes, 0);
  EXPECT_EQ(defaults.collect.actions, "sampled");
  EXPECT_EQ(defaults.collect.seed, 0);
}

TEST(DatasetRecipe, ErrorsNameTheFileAndTheLine) {
  EXPECT_EQ(error_of(std::string(kRecipe) + "colect: {seed: 1}\n"),
            "r.yaml:13: unknown key 'colect' (expected description, grid, collect)");
  EXPECT_EQ(error_of(std::string(kRecipe) + "  colour: red\n"),
            "r.yaml:13: unknown key 'collect.colour' (expected episodes_per_run, random_episodes, actions, seed)");
  std::string zero = kRecipe;
  zero.replace(zero.find("episodes_per_run: 2"), 19, "episodes_per_run: 0");
  EXPECT_EQ(error_of(zero), "r.yaml:9: collect.episodes_per_run must be at least 1, got 0");
  std::string negative = kRecipe;
  negative.replace(negative.find("random_episodes: 1"), 18, "random_episodes: -1");
  EXPECT_EQ(error_of(negative), "r.yaml:10: collect.random_episodes must be at least 0, got -1");
  std::string best = kRecipe;
  best.replace(best.find("actions: mean"), 13, "actions: best");
  EXPECT_EQ(error_of(best), "r.yaml:11: collect.actions must be sampled or mean, got 'best'");
  std::string word = kRecipe;
  word.replace(word.find("seed: 3"), 7, "seed: x");
  EXPECT_EQ(error_of(word), "r.yaml:12: collect.seed must be an integer, got 'x'");
  EXPECT_EQ(error_of("grid: [1, 2]\n"), "r.yaml:1: grid must be a grid file's mapping (envs, seeds, algorithms, ...)");
  EXPECT_EQ(error_of(std::string(kGridOnly) + "collect: 3\n"), "r.yaml:2: collect must be a mapping");
  EXPECT_EQ(error_of("collect: {seed: 1}\n"), "r.yaml: the recipe has no grid");
  EXPECT_EQ(error_of("[1, 2]\n"), "r.yaml: a recipe is a mapping of description, grid and collect");
  const std::string not_yaml = error_of("grid: {envs: [a]\n");
  EXPECT_EQ(not_yaml.rfind("r.yaml:", 0), 0u) << not_yaml;
  EXPECT_NE(not_yaml.find(": not YAML: "), std::string::npos) << not_yaml;

  testing::TemporaryDirectory dir("dataset_recipe");
  const std::string missing = (dir.path() / "missing.yaml").string();
  try {
    load_dataset_recipe(missing);
    ADD_FAILURE() << "a missing recipe was read";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), missing + ": cannot read the recipe");
  }
  testing::write_text_file(dir.path() / "r.yaml", kRecipe);
  EXPECT_EQ(load_dataset_recipe((dir.path() / "r.yaml").string()).collect.seed, 3);
}

TEST(DatasetRecipe, ItsGridFileIsTheGridBlock) {
  const DatasetRecipe recipe = parse_dataset_recipe(kRecipe, "r.yaml");
  const std::string text = recipe_grid_file_text(recipe, "configs/datasets/r.yaml");
  EXPECT_EQ(text.rfind("# The grid of configs/datasets/r.yaml (bsg dataset make)\n", 0), 0u) << text;
  const GridSpec grid = parse_grid(text, "grid.yaml");
  EXPECT_EQ(grid.env_ids, (std::vector<std::string>{"SafetyBallRun-fork", "SafetyBallCircle-v0"}));
  EXPECT_EQ(grid.seeds, (std::vector<std::int64_t>{0}));
  ASSERT_EQ(grid.algorithms.size(), 1u);
  EXPECT_EQ(grid.algorithms[0].alg, Algorithm::lag_trpo);
  ASSERT_EQ(grid.algorithms[0].axes.size(), 1u);
  EXPECT_EQ(grid.algorithms[0].axes[0].values.size(), 2u);
  EXPECT_EQ(default_recipe_out_dir("configs/datasets/ball_fork.yaml"), fs::path("datasets/ball_fork"));
}

PlannedRun planned(const std::string& env_id, const std::string& dir) {
  PlannedRun run;
  run.run.env_id = env_id;
  run.dir = dir;
  return run;
}

TEST(DatasetRecipe, PlansOneFilePerEnvironmentWithItsRunsThenTheRandomPolicy) {
  const DatasetRecipe recipe = parse_dataset_recipe(kRecipe, "r.yaml");
  SweepPlan plan;
  plan.grid.env_ids = {"SafetyBallRun-fork", "SafetyBallCircle-v0"};
  plan.runs = {planned("SafetyBallRun-fork", "s/run/a"), planned("SafetyBallCircle-v0", "s/circle/a"),
               planned("SafetyBallRun-fork", "s/run/b")};
  const std::vector<RecipeDatasetFile> files = plan_recipe_files(recipe, plan, "out", "r.yaml");
  ASSERT_EQ(files.size(), 2u);
  EXPECT_EQ(files[0].env_id, "SafetyBallRun-fork");
  EXPECT_EQ(files[0].file, fs::path("out/SafetyBallRun-fork.hdf5"));
  EXPECT_EQ(files[0].runs, 2);
  ASSERT_EQ(files[0].policies.size(), 3u);
  EXPECT_EQ(files[0].policies[0].source, "s/run/a");
  EXPECT_EQ(files[0].policies[1].source, "s/run/b");
  EXPECT_EQ(files[0].policies[2].source, "random");
  EXPECT_EQ(files[0].policies[0].episodes, 2);
  EXPECT_EQ(files[0].policies[2].episodes, 1);
  EXPECT_EQ(files[0].episodes, 2 * 2 + 1);
  EXPECT_EQ(files[0].seed, 3u);
  EXPECT_EQ(files[0].actions, "mean");
  EXPECT_EQ(files[1].file, fs::path("out/SafetyBallCircle-v0.hdf5"));
  EXPECT_EQ(files[1].runs, 1);
  EXPECT_EQ(files[1].episodes, 1 * 2 + 1);

  // Without random episodes the random policy is left out; an environment nobody collects on is an error.
  const DatasetRecipe no_random = parse_dataset_recipe(std::string(kGridOnly) + "collect: {episodes_per_run: 4}\n", "r.yaml");
  plan.grid.env_ids.push_back("SafetyBallReach-v0");
  try {
    plan_recipe_files(no_random, plan, "out", "r.yaml");
    ADD_FAILURE() << "an environment without policies was planned";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "r.yaml: no policy collects on SafetyBallReach-v0");
  }
  plan.grid.env_ids.pop_back();
  const std::vector<RecipeDatasetFile> runs_only = plan_recipe_files(no_random, plan, "out", "r.yaml");
  ASSERT_EQ(runs_only[0].policies.size(), 2u);
  EXPECT_EQ(runs_only[0].episodes, 8);
  EXPECT_EQ(runs_only[0].actions, "sampled");
}

TEST(DatasetRecipe, EveryShippedRecipeReads) {
  int recipes = 0;
  for (const fs::directory_entry& entry : fs::directory_iterator(fs::path(BSG_SOURCE_DIR) / "configs" / "datasets")) {
    if (entry.path().extension() != ".yaml") continue;
    ++recipes;
    const DatasetRecipe recipe = load_dataset_recipe(entry.path().string());
    EXPECT_GE(recipe.collect.episodes_per_run, 1) << entry.path();
    EXPECT_FALSE(parse_grid(recipe_grid_file_text(recipe, entry.path().string()), "grid.yaml").env_ids.empty())
        << entry.path();
  }
  EXPECT_EQ(recipes, 11);  // the recipes of docs/datasets.md's table
}

}  // namespace
}  // namespace bsg::experiments
