// The plan of `bsg sweep`: the grid's runs (optionally only some
// environments and algorithms), each with its resolved configuration, its
// directory under the sweep's output directory, and its state there
// (finished, resumable from a checkpoint, or to start afresh).
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "common/run_config.h"
#include "experiments/grid_expansion.h"
#include "experiments/run_results.h"

namespace bsg::experiments {

struct PlannedRun {
  GridRun run;
  RunConfig config;
  std::filesystem::path dir;
  RunState state = RunState::fresh;
  int epochs_logged = 0;  // progress.csv rows when the plan was made

  long long training_steps() const;   // epochs x steps_per_epoch
  long long steps_logged() const;     // epochs_logged x steps_per_epoch (all if finished)
  long long evaluation_steps() const; // at most eval_episodes x max_ep_len
};

struct SweepPlanRequest {
  std::filesystem::path grid_file;
  std::filesystem::path configs_dir;
  std::filesystem::path out_dir;
  std::vector<std::string> only_env_ids;     // empty: all of the grid's
  std::vector<std::string> only_algorithms;  // empty: all of the grid's
  int ranks_per_run = 1;
};

struct SweepPlan {
  GridSpec grid;
  std::vector<GridRun> all_runs;  // the whole grid, for the manifest
  std::vector<PlannedRun> runs;   // the ones this sweep covers
};

// Throws ConfigError / std::runtime_error naming the grid, the run or the
// directory at fault: a bad grid or filter, a run whose configuration does
// not resolve or does not suit ranks_per_run, or a run directory that holds
// a run with a different configuration.
SweepPlan make_sweep_plan(const SweepPlanRequest& request);

// Creates the sweep directory (request.out_dir) with a copy of the grid file
// and the manifest of all the grid's runs; the runs' own directories are
// made when they start.
void prepare_sweep_directory(const SweepPlanRequest& request, const SweepPlan& plan);

// Creates a run's directory and writes its resolved run.yaml (atomically), so
// that the run can be started - or reproduced by hand - from it; both
// launchers (local, Slurm) call it before a run starts.
void prepare_run_directory(const PlannedRun& run);

// The listing of --dry-run: one line per run, then the cost in env steps.
std::string dry_run_listing(const SweepPlan& plan);

}  // namespace bsg::experiments
