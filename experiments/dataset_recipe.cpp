#include "experiments/dataset_recipe.h"

#include <yaml-cpp/yaml.h>

#include <stdexcept>
#include <string>

namespace bsg::experiments {
namespace {

[[noreturn]] void recipe_error(const std::string& file, const YAML::Node& node, const std::string& what) {
  const YAML::Mark mark = node.Mark();
  std::string where = file;
  // yaml-cpp counts lines from 0; editors count from 1.
  if (!mark.is_null()) where.append(":").append(std::to_string(mark.line + 1));
  throw std::invalid_argument(where + ": " + what);
}

long long integer_at_least(const std::string& file, const YAML::Node& node, const std::string& key, long long low) {
  long long value = 0;
  try {
    value = node.as<long long>();
  } catch (const YAML::Exception&) {
    recipe_error(file, node, "collect." + key + " must be an integer, got '" + node.as<std::string>("?") + "'");
  }
  if (value < low) {
    recipe_error(file, node, "collect." + key + " must be at least " + std::to_string(low) + ", got " +
                                 std::to_string(value));
  }
  return value;
}

DatasetRecipe recipe_from_root(const YAML::Node& root, const std::string& file) {
  if (!root.IsMap()) throw std::invalid_argument(file + ": a recipe is a mapping of description, grid and collect");
  DatasetRecipe recipe;
  YAML::Node grid;
  for (const auto& entry : root) {
    const std::string key = entry.first.as<std::string>();
    if (key == "description") continue;
    if (key == "grid") {
      if (!entry.second.IsMap()) {
        recipe_error(file, entry.second, "grid must be a grid file's mapping (envs, seeds, algorithms, ...)");
      }
      grid = entry.second;
    } else if (key == "collect") {
      if (!entry.second.IsMap()) recipe_error(file, entry.second, "collect must be a mapping");
      for (const auto& item : entry.second) {
        const std::string name = item.first.as<std::string>();
        if (name == "episodes_per_run") {
          recipe.collect.episodes_per_run = integer_at_least(file, item.second, name, 1);
        } else if (name == "random_episodes") {
          recipe.collect.random_episodes = integer_at_least(file, item.second, name, 0);
        } else if (name == "seed") {
          recipe.collect.seed = integer_at_least(file, item.second, name, 0);
        } else if (name == "actions") {
          recipe.collect.actions = item.second.as<std::string>("");
          if (recipe.collect.actions != "sampled" && recipe.collect.actions != "mean") {
            recipe_error(file, item.second,
                         "collect.actions must be sampled or mean, got '" + recipe.collect.actions + "'");
          }
        } else {
          recipe_error(file, item.first,
                       "unknown key 'collect." + name + "' (expected episodes_per_run, random_episodes, actions, seed)");
        }
      }
    } else {
      recipe_error(file, entry.first, "unknown key '" + key + "' (expected description, grid, collect)");
    }
  }
  // A default-constructed YAML::Node is a defined null node, so `!grid` would never be true.
  if (!grid.IsMap()) throw std::invalid_argument(file + ": the recipe has no grid");
  YAML::Emitter grid_text;
  grid_text << grid;
  recipe.grid_yaml = grid_text.c_str();
  return recipe;
}

}  // namespace

DatasetRecipe load_dataset_recipe(const std::string& file) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(file);
  } catch (const YAML::BadFile&) {
    throw std::invalid_argument(file + ": cannot read the recipe");
  } catch (const YAML::Exception& e) {
    throw std::invalid_argument(file + ":" + std::to_string(e.mark.line + 1) + ": not YAML: " + e.msg);
  }
  return recipe_from_root(root, file);
}

DatasetRecipe parse_dataset_recipe(std::string_view yaml_text, const std::string& file) {
  YAML::Node root;
  try {
    root = YAML::Load(std::string(yaml_text));
  } catch (const YAML::Exception& e) {
    throw std::invalid_argument(file + ":" + std::to_string(e.mark.line + 1) + ": not YAML: " + e.msg);
  }
  return recipe_from_root(root, file);
}

std::string recipe_grid_file_text(const DatasetRecipe& recipe, const std::string& recipe_name) {
  return "# The grid of " + recipe_name + " (bsg dataset make)\n" + recipe.grid_yaml + "\n";
}

std::filesystem::path default_recipe_out_dir(const std::filesystem::path& recipe_file) {
  return std::filesystem::path("datasets") / recipe_file.stem();
}

std::vector<RecipeDatasetFile> plan_recipe_files(const DatasetRecipe& recipe, const SweepPlan& plan,
                                                 const std::filesystem::path& out, const std::string& recipe_name) {
  std::vector<RecipeDatasetFile> files;
  for (const std::string& env_id : plan.grid.env_ids) {
    RecipeDatasetFile file;
    file.env_id = env_id;
    file.file = out / (env_id + ".hdf5");
    file.seed = static_cast<std::uint64_t>(recipe.collect.seed);
    file.actions = recipe.collect.actions;
    for (const PlannedRun& run : plan.runs) {
      if (run.run.env_id != env_id) continue;
      file.policies.push_back({run.dir.string(), recipe.collect.episodes_per_run});
      ++file.runs;
    }
    if (recipe.collect.random_episodes > 0) file.policies.push_back({"random", recipe.collect.random_episodes});
    if (file.policies.empty()) throw std::invalid_argument(recipe_name + ": no policy collects on " + env_id);
    for (const RecipePolicy& policy : file.policies) file.episodes += policy.episodes;
    files.push_back(std::move(file));
  }
  return files;
}

}  // namespace bsg::experiments
