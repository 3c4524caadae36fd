// `bsg sweep GRID`: the command line of a sweep. The grid (configs/grids/
// *.yaml, experiments/grid_file.h) is planned (experiments/sweep_plan.h) and
// run by the local launcher (experiments/local_launcher.h); the sweep
// directory's layout is in experiments/sweep_manifest.h. Exit code 0 iff
// every run of the sweep has finished.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <iostream>
#include <thread>

#include "commands.h"
#include "common/run_config_resolve.h"
#include "experiments/child_process.h"
#include "experiments/local_launcher.h"
#include "experiments/sweep_plan.h"

namespace bsg::cli {

namespace {

struct SweepOptions {
  std::string grid_file;
  int jobs = 0;  // 0: cores / ranks_per_run
  int ranks_per_run = 1;
  std::string out_dir;
  std::string configs_dir;
  bool dry_run = false;
  std::vector<std::string> only_env_ids;
  std::vector<std::string> only_algorithms;
};

int run_sweep(SweepOptions options) {
  const std::filesystem::path grid_file(options.grid_file);
  SweepPlanRequest request;
  request.grid_file = grid_file;
  request.configs_dir = options.configs_dir.empty()
                            ? locate_configs_dir(grid_file.has_parent_path() ? grid_file.parent_path() : ".")
                            : std::filesystem::path(options.configs_dir);
  request.out_dir = options.out_dir.empty() ? std::filesystem::path("sweeps") / grid_file.stem()
                                            : std::filesystem::path(options.out_dir);
  request.only_env_ids = options.only_env_ids;
  request.only_algorithms = options.only_algorithms;
  request.ranks_per_run = options.ranks_per_run;
  if (options.jobs <= 0) {
    const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
    options.jobs = static_cast<int>(std::max(1u, cores / static_cast<unsigned>(options.ranks_per_run)));
  }

  SweepPlan plan = make_sweep_plan(request);
  if (options.dry_run) {
    std::cout << "bsg sweep --dry-run " << grid_file.string() << " -> " << request.out_dir.string() << "\n"
              << dry_run_listing(plan);
    return 0;
  }
  prepare_sweep_directory(request, plan);
  LocalLaunchOptions launch;
  launch.jobs = options.jobs;
  launch.ranks_per_run = options.ranks_per_run;
  launch.configs_dir = request.configs_dir;
  launch.bsg_program = current_executable();
  return run_sweep_locally(std::move(plan), request.out_dir, launch);
}

}  // namespace

void add_sweep_command(CLI::App& app, Action& run) {
  auto options = std::make_shared<SweepOptions>();
  CLI::App* sweep = app.add_subcommand(
      "sweep", "Run a grid of training runs (configs/grids/*.yaml), N at a time; a killed sweep resumes");
  sweep->add_option("GRID", options->grid_file, "grid file, e.g. configs/grids/report.yaml")->required();
  sweep->add_option("--jobs,-j", options->jobs, "runs at a time (default: cores / ranks per run)")
      ->check(CLI::PositiveNumber);
  sweep->add_option("--ranks-per-run", options->ranks_per_run,
                    "MPI processes per run (mpirun -np K bsg train ...)")
      ->check(CLI::PositiveNumber);
  sweep->add_option("--out", options->out_dir, "sweep directory (default: sweeps/<grid name>)");
  sweep->add_option("--configs", options->configs_dir,
                    "configs directory (default: the one at or above the grid file)");
  sweep->add_option("--env", options->only_env_ids, "run only this environment of the grid (repeatable)")
      ->allow_extra_args(false);  // one value per --env: `--env ID GRID` leaves GRID alone
  sweep->add_option("--alg", options->only_algorithms, "run only this algorithm of the grid (repeatable)")
      ->allow_extra_args(false);
  sweep->add_flag("--dry-run", options->dry_run, "list the runs and their cost in env steps; run nothing");
  sweep->callback([options, &run] { run = [options] { return run_sweep(*options); }; });
}

}  // namespace bsg::cli
