// A dataset recipe (configs/datasets/*.yaml, docs/datasets.md#recipes): how a
// set of offline datasets is made, as data. Its `grid:` is a grid file
// (grid_file.h) whose runs are trained by a sweep; then for each of the grid's
// environments one file is collected, <out>/<env id>.hdf5, from every run's
// checkpoint of that environment (in the sweep's order) and the random policy.
//
//   description: free text          (optional)
//   grid: {envs: ..., seeds: ..., algorithms: ...}   (required)
//   collect:                        (optional; the defaults below)
//     episodes_per_run: 10          (>= 1, from every run of the environment)
//     random_episodes: 0            (>= 0, from the random policy)
//     actions: sampled              (or mean)
//     seed: 0                       (>= 0)
//
// Errors are std::invalid_argument with one line naming the file and, where
// it has one, the line.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "experiments/sweep_plan.h"

namespace bsg::experiments {

struct RecipeCollection {
  long long episodes_per_run = 10;
  long long random_episodes = 0;
  std::string actions = "sampled";  // or "mean"
  long long seed = 0;
};

struct DatasetRecipe {
  std::string grid_yaml;  // the grid block, emitted as YAML
  RecipeCollection collect;
};

// Reads and checks a recipe; `file` names it in messages.
DatasetRecipe load_dataset_recipe(const std::string& file);
DatasetRecipe parse_dataset_recipe(std::string_view yaml_text, const std::string& file);

// The grid file a make writes (<out>/grid.yaml) and trains: a comment naming
// the recipe, then the grid.
std::string recipe_grid_file_text(const DatasetRecipe& recipe, const std::string& recipe_name);

// Where a make writes without --out: datasets/<the recipe's file name without extension>.
std::filesystem::path default_recipe_out_dir(const std::filesystem::path& recipe_file);

// One policy of a file's collection: "random" or a run directory, with its episodes.
struct RecipePolicy {
  std::string source;
  long long episodes = 0;
};

// One file of a recipe: a collection counted in episodes, its policies
// sharing them in proportion to their episodes.
struct RecipeDatasetFile {
  std::string env_id;
  std::filesystem::path file;          // <out>/<env id>.hdf5
  long long runs = 0;                  // checkpoints that collect
  std::vector<RecipePolicy> policies;  // the runs in the sweep's order, then the random policy
  long long episodes = 0;              // their sum
  std::uint64_t seed = 0;
  std::string actions;
};

// The files of a recipe whose grid was planned as `plan`, one per
// environment in the grid's order. Throws std::invalid_argument naming
// `recipe_name` and the environment if no policy collects on it.
std::vector<RecipeDatasetFile> plan_recipe_files(const DatasetRecipe& recipe, const SweepPlan& plan,
                                                 const std::filesystem::path& out, const std::string& recipe_name);

}  // namespace bsg::experiments
