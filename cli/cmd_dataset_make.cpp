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
// The recipe's format and the files it collects are experiments/dataset_recipe.h;
// each file is one collection of algos/training/collection_request.h.
#include <CLI/CLI.hpp>
#include <stdlib.h>  // mkdtemp
#include <sys/wait.h>

#include <cerrno>
#include <filesystem>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "algos/training/collection_request.h"
#include "commands.h"
#include "common/atomic_file.h"
#include "configs_search.h"
#include "experiments/child_process.h"
#include "experiments/dataset_recipe.h"
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

experiments::SweepPlan plan_grid(const std::filesystem::path& grid_file, const std::string& configs_dir,
                                 const std::filesystem::path& sweep_dir) {
  experiments::SweepPlanRequest request;
  request.grid_file = grid_file;
  request.configs_dir = configs_dir;
  request.out_dir = sweep_dir;
  return experiments::make_sweep_plan(request);
}

// The grid checked and planned in a scratch folder; nothing under `out` is written.
int dry_run(const MakeArguments& args, const experiments::DatasetRecipe& recipe, const std::string& grid_contents,
            const std::string& configs_dir, const std::filesystem::path& out) {
  char scratch_pattern[] = "/tmp/bsg_dataset_make_XXXXXX";
  if (::mkdtemp(scratch_pattern) == nullptr) throw std::runtime_error("cannot create a scratch folder in /tmp");
  const std::filesystem::path scratch(scratch_pattern);
  try {
    write_file_atomically(scratch / "grid.yaml", grid_contents);
    const experiments::SweepPlan plan = plan_grid(scratch / "grid.yaml", configs_dir, out / "sweep");
    std::cout << "bsg dataset make --dry-run " << args.recipe << " -> " << out.string() << "\n"
              << experiments::dry_run_listing(plan);
    for (const experiments::RecipeDatasetFile& file : experiments::plan_recipe_files(recipe, plan, out, args.recipe)) {
      std::cout << file.file.string() << ": " << file.runs << " runs x " << recipe.collect.episodes_per_run
                << " episodes + " << recipe.collect.random_episodes << " random episodes\n";
    }
  } catch (...) {
    std::filesystem::remove_all(scratch);
    throw;
  }
  std::filesystem::remove_all(scratch);
  return 0;
}

algos::CollectionRequest collection_request(const experiments::RecipeDatasetFile& file) {
  algos::CollectionRequest request;
  request.out = file.file.string();
  request.checkpoint_names_relative_to = file.file.parent_path().string();
  request.env_id = file.env_id;
  request.seed = file.seed;
  request.actions = file.actions == "mean" ? algos::EvaluationActions::mean : algos::EvaluationActions::sampled;
  for (const experiments::RecipePolicy& policy : file.policies) {
    request.policies.push_back({policy.source, static_cast<double>(policy.episodes)});
  }
  request.episodes = file.episodes;
  return request;
}

int make_datasets(const MakeArguments& args) {
  const std::filesystem::path recipe_file(args.recipe);
  const experiments::DatasetRecipe recipe = experiments::load_dataset_recipe(args.recipe);
  const std::filesystem::path out =
      args.out.empty() ? experiments::default_recipe_out_dir(recipe_file) : std::filesystem::path(args.out);
  const std::string grid_contents = experiments::recipe_grid_file_text(recipe, args.recipe);
  const std::string configs_dir = find_configs(args.configs_dir, recipe_file, "recipe").dir.string();
  if (args.dry_run) return dry_run(args, recipe, grid_contents, configs_dir, out);

  std::filesystem::create_directories(out);
  const std::filesystem::path grid = out / "grid.yaml";
  write_file_atomically(grid, grid_contents);
  const std::filesystem::path sweep_dir = out / "sweep";
  std::cout << "training the grid: bsg sweep " << grid.string() << " --out " << sweep_dir.string() << " (log "
            << (out / "sweep.log").string() << ")" << std::endl;
  run_sweep(grid, sweep_dir, out / "sweep.log", configs_dir, args.jobs);

  const experiments::SweepPlan plan = plan_grid(grid, configs_dir, sweep_dir);
  // A make killed during a file's write leaves its temporary behind.
  for (const std::filesystem::path& stale : remove_stale_temporaries(out)) {
    std::cout << "removed " << stale.string() << ", left by an interrupted write\n";
  }
  for (const experiments::RecipeDatasetFile& file : experiments::plan_recipe_files(recipe, plan, out, args.recipe)) {
    if (std::filesystem::exists(file.file)) {
      std::cout << "kept " << file.file.string() << " (made before)\n";
      continue;
    }
    const algos::CollectionSummary summary = algos::collect_to_file(collection_request(file));
    std::cout << "wrote " << file.file.string() << ": " << summary.transitions << " transitions, "
              << summary.episodes << " episodes from " << file.policies.size() << " policies in "
              << summary.seconds << " s (" << summary.bytes << " bytes)" << std::endl;
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
