// The local launcher of a sweep: runs the planned runs as child processes
// `bsg train` on this machine, N at a time (K MPI ranks each under mpirun),
// each holding its run lock. Finished runs are skipped and unfinished ones
// resumed from their checkpoints, so a killed sweep, started again, continues
// where it stopped. Progress goes to stderr (one line, refreshed, on a
// terminal; a line per event otherwise) and every scheduling event to
// sweep_events.csv in the sweep directory (experiments/sweep_events.h).
//
// A stop signal (take_stop_signal returns SIGTERM, SIGINT or SIGHUP) starts
// no new run and is passed on to every running child - as is to `bsg train`,
// as SIGUSR1 to mpirun, which forwards that one to its ranks at once -, so
// that each stops at the end of its epoch with a checkpoint (exit 75, recorded
// as "stopped"); the sweep waits for them all and returns 75. Run again, it
// resumes them.
//
// A run whose lock another process holds (a child of an earlier sweep that
// was killed and left it running) is waited for, not failed: recorded as
// "waiting" with the holder's pid, and once the lock is free, recorded as
// done if that process finished it, else started or resumed here. A run that
// the log shows as started but that has no end (its sweep was killed) gets
// its true state recorded first: done, waiting or interrupted.
#pragma once

#include <filesystem>
#include <functional>

#include "experiments/sweep_plan.h"

namespace bsg::experiments {

struct LocalLaunchOptions {
  int jobs = 1;           // runs at a time (>= 1)
  int ranks_per_run = 1;  // K: mpirun -np K if K > 1
  std::filesystem::path configs_dir;  // handed to each new run's `bsg train --configs`
  std::filesystem::path bsg_program;  // the `bsg` executable the children run
  // The stop signal received since the last call (and consumed), or 0.
  std::function<int()> take_stop_signal = [] { return 0; };
};

inline constexpr int kSweepExitStopped = 75;  // as `bsg train` (cli/stop_signals.h)

// Runs every unfinished run of the plan; returns 0 iff all have finished,
// kSweepExitStopped if a stop signal ended it, else 1 if any failed (each
// failure is listed on stderr with its log path).
int run_sweep_locally(SweepPlan plan, const std::filesystem::path& sweep_dir,
                      const LocalLaunchOptions& options);

}  // namespace bsg::experiments
