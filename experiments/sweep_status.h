// `bsg sweep --status DIR`: the state of every run of a sweep directory,
// local or Slurm, read from the files (manifest, run directories, run locks,
// sweep_events.csv, slurm_jobs.csv) and, for a Slurm sweep, from squeue.
//   finished     evaluation.json exists
//   running      its lock is held (a `bsg train` runs it), or squeue says so
//   queued       its Slurm task is pending
//   failed       its last attempt ended without finishing (a local sweep's
//                "failed" event, or a Slurm task no longer in the queue)
//   stopped      has a checkpoint, not running, no failure recorded
//   not started  nothing yet
// The ETA divides the epochs left, each at its run's measured seconds per
// epoch (progress.csv's time_s; a run without timings takes the mean of the
// runs of its environment, else of all), by the number of runs running now.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace bsg::experiments {

enum class SweepRunStatus { finished, running, queued, failed, stopped, not_started };
const char* to_string(SweepRunStatus status);

struct SweepRunReport {
  std::filesystem::path run_dir;  // relative to the sweep directory
  std::string env_id;
  SweepRunStatus status = SweepRunStatus::not_started;
  int epochs_done = 0;
  std::optional<int> epochs_total;             // from run.yaml, if written yet
  std::optional<double> seconds_per_epoch;     // measured, if any epoch is logged
  std::filesystem::path log;                   // train.log
  std::string detail;                          // why it failed, the Slurm task id, ...
};

struct SweepStatus {
  std::filesystem::path sweep_dir;
  std::vector<SweepRunReport> runs;
  bool slurm = false;
  std::string note;  // e.g. squeue could not be asked
};

// Throws std::runtime_error if `sweep_dir` is not a sweep directory (no
// sweep_runs.csv) or one of its files is malformed.
SweepStatus read_sweep_status(const std::filesystem::path& sweep_dir);

// Seconds left, or nullopt if some unfinished run's length or pace is
// unknown and nothing is measured at all.
std::optional<double> sweep_eta_seconds(const SweepStatus& status);

// The report: counts, one line per run, the ETA, the failed runs' logs.
std::string sweep_status_text(const SweepStatus& status);

}  // namespace bsg::experiments
