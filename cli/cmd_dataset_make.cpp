// `bsg dataset make RECIPE [--out DIR] [--jobs N] [--configs DIR]`: a dataset
// recipe (configs/datasets/*.yaml, docs/datasets.md#recipes) run end to end.
// Its `grid:` is a grid file (configs/grids/README.md), written to
// DIR/grid.yaml and trained by `bsg sweep` into DIR/sweep (log in
// DIR/sweep.log); then for each of the grid's environments every run's
// checkpoint (episodes_per_run episodes each, in the sweep's order) and the
// random policy (random_episodes) are collected into DIR/<env id>.hdf5.
// Everything resumes: the sweep continues its runs, and a file already made is
// kept, so running the command again after an interruption finishes the job
// with the files an uninterrupted one would have written.
#include <CLI/CLI.hpp>
#include <stdlib.h>  // mkdtemp
#include <sys/wait.h>
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <iostream>
#include <memory>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "commands.h"
#include "common/atomic_file.h"
#include "configs_search.h"
#include "dataset_collection.h"
#include "experiments/child_process.h"
#include "experiments/sweep_plan.h"

namespace bsg::cli {
namespace {

struct MakeArguments {
  std::string recipe;
  std::string out;
  int jobs = 1;
  std::string configs_dir;
  bool dry_run = false;
};

struct CollectRecipe {
  long long episodes_per_run = 10;
  long long random_episodes = 0;
  std::string actions = "sampled";
  long long seed = 0;
};

struct Recipe {
  YAML::Node grid;
  CollectRecipe collect;
};

[[noreturn]] void recipe_error(const std::string& file, const YAML::Node& node, const std::string& what) {
  const YAML::Mark mark = node.Mark();
  throw std::invalid_argument(file + (mark.is_null() ? "" : ":" + std::to_string(mark.line + 1)) + ": " + what);
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

Recipe load_recipe(const std::string& file) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(file);
  } catch (const YAML::BadFile&) {
    throw std::invalid_argument(file + ": cannot read the recipe");
  } catch (const YAML::Exception& e) {
    throw std::invalid_argument(file + ":" + std::to_string(e.mark.line + 1) + ": not YAML: " + e.msg);
  }
  if (!root.IsMap()) throw std::invalid_argument(file + ": a recipe is a mapping of description, grid and collect");
  Recipe recipe;
  for (const auto& entry : root) {
    const std::string key = entry.first.as<std::string>();
    if (key == "description") continue;
    if (key == "grid") {
      if (!entry.second.IsMap()) recipe_error(file, entry.second, "grid must be a grid file's mapping (envs, seeds, algorithms, ...)");
      recipe.grid = entry.second;
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
            recipe_error(file, item.second, "collect.actions must be sampled or mean, got '" + recipe.collect.actions + "'");
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
  if (!recipe.grid) throw std::invalid_argument(file + ": the recipe has no grid");
  return recipe;
}

// Runs `bsg sweep` on the grid and waits for it; its output goes to the log.
void run_sweep(const std::filesystem::path& grid, const std::filesystem::path& sweep_dir,
               const std::filesystem::path& log, const std::string& configs_dir, int jobs) {
  experiments::ChildCommand command;
  command.argv = {experiments::current_executable().string(), "sweep", grid.string(), "--out", sweep_dir.string(),
                  "--jobs", std::to_string(jobs), "--configs", configs_dir};
  command.log_file = log;
  const pid_t pid = experiments::start_child(command);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) throw std::runtime_error("cannot wait for bsg sweep");
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    throw std::runtime_error("the sweep did not finish (" +
                             (WIFEXITED(status) ? "exit code " + std::to_string(WEXITSTATUS(status))
                                                : "killed by " + experiments::signal_name(WTERMSIG(status))) +
                             ", " + log.string() + " says why); run bsg dataset make again to resume");
  }
}

int make_datasets(const MakeArguments& args) {
  const std::filesystem::path recipe_file(args.recipe);
  const Recipe recipe = load_recipe(args.recipe);
  const std::filesystem::path out =
      args.out.empty() ? std::filesystem::path("datasets") / recipe_file.stem() : std::filesystem::path(args.out);
  YAML::Emitter grid_text;
  grid_text << recipe.grid;
  const std::string grid_contents =
      std::string("# The grid of ") + args.recipe + " (bsg dataset make)\n" + grid_text.c_str() + "\n";
  const std::string configs_dir = find_configs(args.configs_dir, recipe_file, "recipe").dir.string();
  if (args.dry_run) {
    // The grid checked and planned in a scratch folder; nothing under `out` is written.
    char scratch_pattern[] = "/tmp/bsg_dataset_make_XXXXXX";
    if (::mkdtemp(scratch_pattern) == nullptr) throw std::runtime_error("cannot create a scratch folder in /tmp");
    const std::filesystem::path scratch(scratch_pattern);
    try {
      write_file_atomically(scratch / "grid.yaml", grid_contents);
      experiments::SweepPlanRequest request;
      request.grid_file = scratch / "grid.yaml";
      request.configs_dir = configs_dir;
      request.out_dir = out / "sweep";
      const experiments::SweepPlan plan = experiments::make_sweep_plan(request);
      std::cout << "bsg dataset make --dry-run " << args.recipe << " -> " << out.string() << "\n"
                << experiments::dry_run_listing(plan);
      for (const std::string& env_id : plan.grid.env_ids) {
        long long runs = 0;
        for (const experiments::PlannedRun& run : plan.runs) runs += run.run.env_id == env_id ? 1 : 0;
        std::cout << (out / (env_id + ".hdf5")).string() << ": " << runs << " runs x "
                  << recipe.collect.episodes_per_run << " episodes + " << recipe.collect.random_episodes
                  << " random episodes\n";
      }
    } catch (...) {
      std::filesystem::remove_all(scratch);
      throw;
    }
    std::filesystem::remove_all(scratch);
    return 0;
  }
  std::filesystem::create_directories(out);
  const std::filesystem::path grid = out / "grid.yaml";
  write_file_atomically(grid, grid_contents);
  const std::filesystem::path sweep_dir = out / "sweep";
  std::cout << "training the grid: bsg sweep " << grid.string() << " --out " << sweep_dir.string() << " (log "
            << (out / "sweep.log").string() << ")" << std::endl;
  run_sweep(grid, sweep_dir, out / "sweep.log", configs_dir, args.jobs);

  experiments::SweepPlanRequest request;
  request.grid_file = grid;
  request.configs_dir = configs_dir;
  request.out_dir = sweep_dir;
  const experiments::SweepPlan plan = experiments::make_sweep_plan(request);
  // A make killed during a file's write leaves its temporary behind.
  for (const std::filesystem::path& stale : remove_stale_temporaries(out)) {
    std::cout << "removed " << stale.string() << ", left by an interrupted write\n";
  }
  for (const std::string& env_id : plan.grid.env_ids) {
    const std::filesystem::path file = out / (env_id + ".hdf5");
    if (std::filesystem::exists(file)) {
      std::cout << "kept " << file.string() << " (made before)\n";
      continue;
    }
    CollectArguments collect;
    collect.out = file.string();
    collect.env_id = env_id;
    collect.seed = static_cast<std::uint64_t>(recipe.collect.seed);
    collect.actions = recipe.collect.actions;
    long long episodes = 0;
    for (const experiments::PlannedRun& run : plan.runs) {
      if (run.run.env_id != env_id) continue;
      collect.policies.push_back(run.dir.string() + "=" + std::to_string(recipe.collect.episodes_per_run));
      episodes += recipe.collect.episodes_per_run;
    }
    if (recipe.collect.random_episodes > 0) {
      collect.policies.push_back("random=" + std::to_string(recipe.collect.random_episodes));
      episodes += recipe.collect.random_episodes;
    }
    if (collect.policies.empty()) throw std::invalid_argument(args.recipe + ": no policy collects on " + env_id);
    collect.episodes = episodes;
    const CollectSummary summary = collect_to_file(collect);
    std::cout << "wrote " << file.string() << ": " << summary.transitions << " transitions, " << summary.episodes
              << " episodes from " << collect.policies.size() << " policies in " << summary.seconds << " s ("
              << summary.bytes << " bytes)" << std::endl;
  }
  return 0;
}

}  // namespace

void add_dataset_make_command(CLI::App& dataset, Action& run) {
  CLI::App* make = dataset.add_subcommand(
      "make", "Run a dataset recipe: train its grid with bsg sweep, then collect one file per environment");
  auto args = std::make_shared<MakeArguments>();
  make->add_option("RECIPE", args->recipe, "a recipe, e.g. configs/datasets/ball_fork.yaml")->required();
  make->add_option("--out", args->out, "output folder (default datasets/<recipe name>)");
  make->add_option("--jobs", args->jobs, "training runs at a time (default 1)")->check(CLI::PositiveNumber);
  make->add_option("--configs", args->configs_dir, "configs folder (default: searched from the recipe's folder)");
  make->add_flag("--dry-run", args->dry_run, "check the recipe and list its runs and files; write nothing");
  make->callback([&run, args]() { run = [args]() { return make_datasets(*args); }; });
}

}  // namespace bsg::cli
