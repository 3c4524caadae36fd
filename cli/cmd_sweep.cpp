// `bsg sweep GRID`: the command line of a sweep. The grid (configs/grids/
// *.yaml, experiments/grid_file.h) is planned (experiments/sweep_plan.h) and
// run by the local launcher (experiments/local_launcher.h) or, with --slurm,
// submitted as a Slurm job array (experiments/slurm_launcher.h); the sweep
// directory's layout is in experiments/sweep_manifest.h. Exit code of a
// local sweep: 0 iff every run has finished, 75 if SIGTERM, SIGINT or SIGHUP
// stopped it (its running runs stop with a checkpoint; run it again to
// resume); of --slurm: 0 iff submitted. One sweep at a time holds a sweep
// directory (<dir>/sweep.lock); a second one names the first's pid and exits 1.
// `bsg sweep --status DIR` reports a sweep of either kind
// (experiments/sweep_status.h).
#include <CLI/CLI.hpp>

#include <algorithm>

#include <iostream>
#include <optional>
#include <thread>

#include "commands.h"
#include "configs_search.h"
#include "experiments/child_process.h"
#include "experiments/local_launcher.h"
#include "experiments/run_lock.h"
#include "experiments/slurm_launcher.h"
#include "experiments/sweep_plan.h"
#include "experiments/sweep_status.h"
#include "stop_signals.h"

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
  bool slurm = false;
  experiments::SlurmJobOptions slurm_job;
  std::string status_dir;
};

int run_sweep(SweepOptions options) {
  const std::filesystem::path grid_file(options.grid_file);
  experiments::SweepPlanRequest request;
  request.grid_file = grid_file;
  request.configs_dir = find_configs(options.configs_dir, grid_file, "grid file").dir;
  request.out_dir = options.out_dir.empty() ? std::filesystem::path("sweeps") / grid_file.stem()
                                            : std::filesystem::path(options.out_dir);
  request.only_env_ids = options.only_env_ids;
  request.only_algorithms = options.only_algorithms;
  request.ranks_per_run = options.ranks_per_run;
  if (options.jobs <= 0) {
    const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
    options.jobs = static_cast<int>(std::max(1u, cores / static_cast<unsigned>(options.ranks_per_run)));
  }

  if (options.dry_run && !options.slurm) {
    std::cout << "bsg sweep --dry-run " << grid_file.string() << " -> " << request.out_dir.string() << "\n"
              << experiments::dry_run_listing(experiments::make_sweep_plan(request));
    return 0;
  }
  const std::optional<experiments::RunLock> sweep_lock =
      options.dry_run ? std::nullopt : std::optional<experiments::RunLock>(experiments::lock_sweep_directory(request.out_dir, std::cerr));
  experiments::SweepPlan plan = experiments::make_sweep_plan(request);
  if (options.slurm) {
    experiments::SlurmLaunchOptions launch;
    launch.job = options.slurm_job;
    launch.job.ranks_per_run = options.ranks_per_run;
    launch.configs_dir = request.configs_dir;
    launch.bsg_program = experiments::current_executable();
    launch.dry_run = options.dry_run;
    if (!options.dry_run) experiments::prepare_sweep_directory(request, plan);
    return experiments::submit_sweep_to_slurm(plan, request.out_dir, launch, std::cout);
  }
  experiments::prepare_sweep_directory(request, plan);
  // Blocked before the first child starts (children unblock them, experiments/child_process.h).
  const StopSignals stop_signals;
  experiments::LocalLaunchOptions launch;
  launch.jobs = options.jobs;
  launch.ranks_per_run = options.ranks_per_run;
  launch.configs_dir = request.configs_dir;
  launch.bsg_program = experiments::current_executable();
  launch.take_stop_signal = [&stop_signals] { return stop_signals.take_pending(); };
  return experiments::run_sweep_locally(std::move(plan), request.out_dir, launch);
}

}  // namespace

void add_sweep_command(CLI::App& app, Action& run) {
  auto options = std::make_shared<SweepOptions>();
  CLI::App* sweep = app.add_subcommand(
      "sweep", "Run a grid of training runs (configs/grids/*.yaml), N at a time; a killed sweep resumes");
  sweep->add_option("GRID", options->grid_file, "grid file, e.g. configs/grids/report.yaml");
  auto* jobs = sweep->add_option("--jobs,-j", options->jobs, "runs at a time (default: cores / ranks per run)")
                   ->check(CLI::PositiveNumber);
  sweep->add_option("--ranks-per-run", options->ranks_per_run,
                    "MPI processes per run (mpirun -np K bsg train ...)")
      ->check(CLI::PositiveNumber);
  sweep->add_option("--out", options->out_dir, "sweep directory (default: sweeps/<grid name>)");
  sweep->add_option("--configs", options->configs_dir,
                    "configs folder (default: searched as by bsg train, from the grid file's folder)");
  sweep->add_option("--env", options->only_env_ids, "run only this environment of the grid (repeatable)")
      ->allow_extra_args(false);  // one value per --env: `--env ID GRID` leaves GRID alone
  sweep->add_option("--alg", options->only_algorithms, "run only this algorithm of the grid (repeatable)")
      ->allow_extra_args(false);
  sweep->add_flag("--dry-run", options->dry_run, "list the runs and their cost in env steps; run nothing");
  auto* slurm = sweep->add_flag("--slurm", options->slurm,
                                "submit the runs as one Slurm job array (sbatch) instead of running them here");
  std::vector<CLI::Option*> slurm_only = {
      sweep->add_option("--partition", options->slurm_job.partition, "Slurm partition (--slurm)"),
      sweep->add_option("--time", options->slurm_job.time_limit,
                        "Slurm time limit per run, e.g. 12:00:00 (--slurm)"),
      sweep->add_option("--max-running", options->slurm_job.max_running,
                        "at most this many array tasks at once: the %M throttle (--slurm)")
          ->check(CLI::PositiveNumber),
      sweep->add_option("--sbatch-arg", options->slurm_job.sbatch_args,
                        "one more sbatch option, e.g. --sbatch-arg=--account=abc (--slurm, repeatable)")
          ->allow_extra_args(false)};
  for (CLI::Option* option : slurm_only) option->needs(slurm);
  jobs->excludes(slurm);  // Slurm decides; --max-running throttles
  auto* status = sweep->add_option("--status", options->status_dir,
                                   "report the sweep in this directory (local or Slurm) and exit");
  status->excludes(slurm);
  sweep->callback([options, &run] {
    if (!options->status_dir.empty()) {
      if (!options->grid_file.empty()) throw CLI::ValidationError("--status", "takes a sweep directory, not GRID");
      run = [options] {
        std::cout << experiments::sweep_status_text(experiments::read_sweep_status(options->status_dir));
        return 0;
      };
      return;
    }
    if (options->grid_file.empty()) throw CLI::RequiredError("GRID (or --status SWEEP_DIR)");
    run = [options] { return run_sweep(*options); };
  });
}

}  // namespace bsg::cli
