// The local launcher of a sweep: runs the planned runs as child processes
// `bsg train` on this machine, N at a time (K MPI ranks each under mpirun),
// each holding its run lock. Finished runs are skipped and unfinished ones
// resumed from their checkpoints, so a killed sweep, started again, continues
// where it stopped. Progress goes to stderr (one line, refreshed, on a
// terminal; a line per event otherwise) and every scheduling event to
// sweep_events.csv in the sweep directory.
#pragma once

#include <filesystem>

#include "experiments/sweep_plan.h"

namespace bsg {

struct LocalLaunchOptions {
  int jobs = 1;           // runs at a time (>= 1)
  int ranks_per_run = 1;  // K: mpirun -np K if K > 1
  std::filesystem::path configs_dir;  // handed to each new run's `bsg train --configs`
  std::filesystem::path bsg_program;  // the `bsg` executable the children run
};

// Runs every unfinished run of the plan; returns 0 iff all have finished,
// 1 if any failed (each failure is listed on stderr with its log path).
int run_sweep_locally(SweepPlan plan, const std::filesystem::path& sweep_dir,
                      const LocalLaunchOptions& options);

}  // namespace bsg
