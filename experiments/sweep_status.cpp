#include "experiments/sweep_status.h"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <map>
#include <stdexcept>

#include "algos/training/progress_line.h"
#include "algos/training/run_directory.h"
#include "common/csv_text.h"
#include "common/run_config_yaml.h"
#include "experiments/captured_program.h"
#include "experiments/run_lock.h"
#include "experiments/sweep_events.h"
#include "experiments/run_results.h"
#include "experiments/slurm_jobs.h"
#include "experiments/sweep_manifest.h"

namespace bsg::experiments {

namespace {

// Mean wall seconds per epoch from progress.csv: the last row's time_s over
// the rows; nullopt without rows or without the column.
std::optional<double> measured_seconds_per_epoch(const algos::RunDirectory& directory) {
  std::ifstream file(directory.progress());
  std::string header;
  if (!file || !std::getline(file, header)) return std::nullopt;
  const std::vector<std::string> names = parse_csv_fields(header);
  const auto column = std::find(names.begin(), names.end(), "time_s");
  if (column == names.end()) return std::nullopt;
  std::string line;
  std::string last;
  int rows = 0;
  while (std::getline(file, line)) {
    if (line.empty()) continue;
    last = line;
    ++rows;
  }
  if (rows == 0) return std::nullopt;
  const std::vector<std::string> fields = parse_csv_fields(last);
  const auto index = static_cast<std::size_t>(column - names.begin());
  if (index >= fields.size()) return std::nullopt;
  try {
    return std::stod(fields[index]) / rows;
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

bool lock_held(const std::filesystem::path& run_dir) {
  if (!std::filesystem::exists(run_dir / kRunLockName)) return false;
  try {
    return !RunLock::try_acquire(run_dir).has_value();
  } catch (const std::exception&) {
    return false;  // unreadable lock file (e.g. another user's): the other sources decide
  }
}

}  // namespace

const char* to_string(SweepRunStatus status) {
  switch (status) {
    case SweepRunStatus::finished: return "finished";
    case SweepRunStatus::running: return "running";
    case SweepRunStatus::queued: return "queued";
    case SweepRunStatus::failed: return "failed";
    case SweepRunStatus::stopped: return "stopped";
    case SweepRunStatus::not_started: return "not started";
  }
  return "?";
}

SweepStatus read_sweep_status(const std::filesystem::path& sweep_dir) {
  if (!std::filesystem::is_regular_file(sweep_dir / kSweepManifestName)) {
    throw std::runtime_error(sweep_dir.string() + " is not a sweep directory (it has no " + kSweepManifestName +
                             "; `bsg sweep GRID --out DIR` makes one)");
  }
  SweepStatus status;
  status.sweep_dir = sweep_dir;
  const std::vector<GridRun> manifest = read_sweep_manifest(sweep_dir);
  const std::vector<SlurmTaskRecord> records = read_slurm_records(sweep_dir);
  status.slurm = !records.empty();
  std::map<std::string, SlurmTaskState> tasks;
  if (status.slurm) {
    if (!find_on_path("squeue")) {
      status.note = "squeue is not on PATH: queued and running Slurm tasks show from the run files only";
    } else {
      try {
        tasks = query_slurm_tasks();
      } catch (const std::exception& e) {
        status.note = std::string("squeue could not be asked (") + e.what() + "): states from the run files only";
      }
    }
  }
  const auto latest = latest_record_per_run(records);
  const auto events = last_sweep_events(sweep_dir);

  for (const GridRun& run : manifest) {
    SweepRunReport report;
    report.run_dir = run.relative_dir();
    report.env_id = run.env_id;
    const std::filesystem::path dir = sweep_dir / report.run_dir;
    const algos::RunDirectory directory(dir);
    report.log = dir / kSweepRunLogName;
    report.epochs_done = logged_epochs(directory);
    report.seconds_per_epoch = measured_seconds_per_epoch(directory);
    if (std::filesystem::is_regular_file(dir / kSweepRunFileName)) {
      try {
        report.epochs_total = load_resolved_run_config(dir / kSweepRunFileName).epochs;
      } catch (const std::exception&) {
        report.detail = "unreadable " + std::string(kSweepRunFileName);
      }
    }
    const auto record = latest.find(report.run_dir);
    const auto task = record == latest.end() ? tasks.end() : tasks.find(record->second.task_id());
    const auto event = events.find(report.run_dir);
    if (record != latest.end()) report.detail = "slurm task " + record->second.task_id();
    if (run_state(directory) == RunState::finished) {
      report.status = SweepRunStatus::finished;
      if (report.epochs_total) report.epochs_done = *report.epochs_total;
    } else if (lock_held(dir) || (task != tasks.end() && task->second == SlurmTaskState::running)) {
      report.status = SweepRunStatus::running;
    } else if (task != tasks.end()) {
      report.status = SweepRunStatus::queued;
    } else if (record != latest.end() && status.note.empty()) {
      report.status = SweepRunStatus::failed;  // its task left the queue unfinished
      report.detail += " ended unfinished";
    } else if (event != events.end() && event->second.first == "failed") {
      report.status = SweepRunStatus::failed;
      report.detail = event->second.second;
    } else {
      report.status = report.epochs_done > 0 ? SweepRunStatus::stopped : SweepRunStatus::not_started;
    }
    status.runs.push_back(std::move(report));
  }
  return status;
}

std::optional<double> sweep_eta_seconds(const SweepStatus& status) {
  std::map<std::string, std::pair<double, int>> pace_by_env;  // sum of s/epoch, runs
  double pace_sum = 0;
  int paced = 0;
  std::map<std::string, int> epochs_by_env;  // a known run length per environment
  for (const SweepRunReport& run : status.runs) {
    if (run.seconds_per_epoch) {
      auto& [sum, count] = pace_by_env[run.env_id];
      sum += *run.seconds_per_epoch;
      ++count;
      pace_sum += *run.seconds_per_epoch;
      ++paced;
    }
    if (run.epochs_total) epochs_by_env[run.env_id] = *run.epochs_total;
  }
  if (paced == 0) return std::nullopt;
  double seconds = 0;
  int running = 0;
  for (const SweepRunReport& run : status.runs) {
    if (run.status == SweepRunStatus::finished) continue;
    if (run.status == SweepRunStatus::running) ++running;
    std::optional<int> total = run.epochs_total;
    if (!total && epochs_by_env.count(run.env_id) != 0) total = epochs_by_env.at(run.env_id);
    if (!total) return std::nullopt;
    double pace = pace_sum / paced;
    if (run.seconds_per_epoch) {
      pace = *run.seconds_per_epoch;
    } else if (const auto found = pace_by_env.find(run.env_id); found != pace_by_env.end()) {
      pace = found->second.first / found->second.second;
    }
    seconds += std::max(0, *total - run.epochs_done) * pace;
  }
  return seconds / std::max(1, running);
}

std::string sweep_status_text(const SweepStatus& status) {
  std::map<SweepRunStatus, int> counts;
  for (const SweepRunReport& run : status.runs) ++counts[run.status];
  std::string text = "sweep " + status.sweep_dir.string() + (status.slurm ? " (Slurm): " : ": ") +
                     std::to_string(status.runs.size()) + " runs: ";
  const SweepRunStatus order[] = {SweepRunStatus::finished, SweepRunStatus::running, SweepRunStatus::queued,
                                  SweepRunStatus::failed,   SweepRunStatus::stopped, SweepRunStatus::not_started};
  bool first = true;
  for (const SweepRunStatus state : order) {
    if (state == SweepRunStatus::stopped && counts[state] == 0) continue;
    text += (first ? "" : ", ") + std::to_string(counts[state]) + " " + to_string(state);
    first = false;
  }
  text += "\nstate         epochs   s/epoch  run directory\n";
  for (const SweepRunReport& run : status.runs) {
    char line[96];
    const std::string epochs =
        std::to_string(run.epochs_done) + "/" + (run.epochs_total ? std::to_string(*run.epochs_total) : "?");
    const std::string pace = run.seconds_per_epoch ? [&] {
      char value[32];
      std::snprintf(value, sizeof value, "%.3g", *run.seconds_per_epoch);
      return std::string(value);
    }()
                                                   : std::string("-");
    std::snprintf(line, sizeof line, "%-12s %7s %9s  ", to_string(run.status), epochs.c_str(), pace.c_str());
    text += line + run.run_dir.generic_string() + (run.detail.empty() ? "" : "  (" + run.detail + ")") + "\n";
  }
  if (counts[SweepRunStatus::finished] == static_cast<int>(status.runs.size())) {
    text += "all runs finished; `bsg table " + status.sweep_dir.string() + "` tabulates them\n";
  } else if (const std::optional<double> eta = sweep_eta_seconds(status)) {
    text += "ETA " + algos::format_duration(*eta) + " (epochs left at their runs' measured epoch times, " +
            std::to_string(std::max(1, counts[SweepRunStatus::running])) + " at a time)\n";
  } else {
    text += "ETA unknown (no epoch timed yet, or a run's length is not known yet)\n";
  }
  if (counts[SweepRunStatus::failed] > 0) {
    text += "failed runs (submit the sweep again to retry them):\n";
    for (const SweepRunReport& run : status.runs) {
      if (run.status == SweepRunStatus::failed) text += "  " + run.run_dir.generic_string() + "  log: " + run.log.string() + "\n";
    }
  }
  if (!status.note.empty()) text += "note: " + status.note + "\n";
  return text;
}

}  // namespace bsg::experiments
