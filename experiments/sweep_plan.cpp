#include "experiments/sweep_plan.h"

#include <algorithm>
#include <cstdio>
#include <set>
#include <sstream>
#include <stdexcept>

#include "algos/training/dataset_location.h"
#include "algos/training/run_directory.h"
#include "common/algorithms.h"
#include "common/atomic_file.h"
#include "common/file_reading.h"
#include "common/config_error.h"
#include "common/run_config_checks.h"
#include "common/run_config_yaml.h"
#include "experiments/sweep_manifest.h"
#include "experiments/sweep_progress.h"

namespace bsg::experiments {

namespace {

// The first line where two resolved configurations differ (log_dir aside:
// the sweep chooses each run's directory itself).
std::string first_difference(RunConfig a, RunConfig b) {
  a.log_dir = b.log_dir;
  std::istringstream left(to_yaml(a));
  std::istringstream right(to_yaml(b));
  std::string l;
  std::string r;
  while (std::getline(left, l)) {
    if (!std::getline(right, r)) return "'" + l + "' versus nothing";
    if (l != r) return "'" + l + "' versus '" + r + "'";
  }
  return "";
}

template <typename Item>
void check_filter(const std::vector<std::string>& filter, const std::vector<Item>& present,
                  const std::string& what, const std::string& grid_name) {
  for (const std::string& wanted : filter) {
    if (std::find(present.begin(), present.end(), wanted) == present.end()) {
      std::string list;
      for (const auto& item : present) list += (list.empty() ? "" : ", ") + std::string(item);
      throw ConfigError("--" + what + " " + wanted + ": not in the grid " + grid_name + " (it has " +
                        list + ")");
    }
  }
}

// The configuration as bsg train records it in config.yaml: an offline run's
// dataset becomes the absolute file it learns from (a directory gives its
// <env_id>.hdf5), so that a finished or interrupted run of the same grid
// compares equal. A location that names no file yet is left as it is (the
// comparison then names it).
RunConfig as_recorded(RunConfig config) {
  if (is_offline(config.alg) && !config.offline.dataset.empty()) {
    try {
      config.offline.dataset = algos::locate_dataset(config.offline.dataset, config.env_id).string();
    } catch (const std::invalid_argument&) {
    }
  }
  return config;
}

bool selected(const std::vector<std::string>& filter, const std::string& value) {
  return filter.empty() || std::find(filter.begin(), filter.end(), value) != filter.end();
}

}  // namespace

long long PlannedRun::training_steps() const {
  return static_cast<long long>(config.epochs) * config.steps_per_epoch;
}

long long PlannedRun::steps_logged() const {
  if (state == RunState::finished) return training_steps();
  return std::min(training_steps(), static_cast<long long>(epochs_logged) * config.steps_per_epoch);
}

long long PlannedRun::evaluation_steps() const {
  return static_cast<long long>(config.eval_episodes) * config.max_ep_len;
}

SweepPlan make_sweep_plan(const SweepPlanRequest& request) {
  SweepPlan plan;
  plan.grid = load_grid_file(request.grid_file);
  plan.all_runs = expand_grid(plan.grid);
  const std::string grid_name = request.grid_file.string();

  std::vector<std::string> alg_names;
  for (const AlgorithmGrid& algorithm : plan.grid.algorithms) {
    alg_names.emplace_back(to_string(algorithm.alg));
  }
  check_filter(request.only_env_ids, plan.grid.env_ids, "env", grid_name);
  check_filter(request.only_algorithms, alg_names, "alg", grid_name);

  std::set<std::string> ranks_checked;  // one check per (env, alg, config)
  for (const GridRun& run : plan.all_runs) {
    if (!selected(request.only_env_ids, run.env_id) ||
        !selected(request.only_algorithms, std::string(to_string(run.alg)))) {
      continue;
    }
    PlannedRun planned;
    planned.run = run;
    planned.config = resolve_grid_run(run, request.configs_dir, grid_name);
    planned.dir = request.out_dir / run.relative_dir();
    planned.config.log_dir = request.out_dir.string();
    const std::string config_dir = run.relative_dir().parent_path().string();
    if (ranks_checked.insert(config_dir).second) {
      try {
        check_run_config_for_ranks(planned.config, request.ranks_per_run);
      } catch (const std::exception& e) {
        throw ConfigError(grid_name + ": run " + run.relative_dir().string() + " with --ranks-per-run " +
                          std::to_string(request.ranks_per_run) + ": " + e.what());
      }
    }
    const algos::RunDirectory directory(planned.dir);
    planned.state = run_state(directory);
    planned.epochs_logged = logged_epochs(directory);
    std::error_code error;
    if (std::filesystem::is_regular_file(directory.config(), error)) {
      const RunConfig existing = load_resolved_run_config(directory.config());
      const std::string difference = first_difference(existing, as_recorded(planned.config));
      if (!difference.empty()) {
        throw std::runtime_error(
            directory.config().string() + " holds a run of another configuration than the grid " +
            grid_name + " asks for (" + difference + "); remove the directory or choose another --out");
      }
    }
    plan.runs.push_back(std::move(planned));
  }
  return plan;
}

void prepare_sweep_directory(const SweepPlanRequest& request, const SweepPlan& plan) {
  std::filesystem::create_directories(request.out_dir);
  // Atomic, as every file of the sweep directory (common/atomic_file.h).
  write_file_atomically(request.out_dir / kSweepGridCopyName, read_regular_file(request.grid_file, "grid file"));
  write_sweep_manifest(request.out_dir, plan.all_runs);
}

void prepare_run_directory(const PlannedRun& run) {
  std::filesystem::create_directories(run.dir);
  write_file_atomically(run.dir / kSweepRunFileName, to_run_file_yaml(run.config));
}

std::string dry_run_listing(const SweepPlan& plan) {
  std::string text = "state      epochs       env steps  run directory\n";
  long long total = 0;
  long long logged = 0;
  long long evaluation = 0;
  long long offline_updates = 0;
  long long offline_updates_left = 0;
  std::size_t counts[3] = {0, 0, 0};
  std::set<std::string> configurations;
  for (const PlannedRun& run : plan.runs) {
    char line[128];
    const int epochs_done = run.state == RunState::finished ? run.config.epochs
                                                            : std::min(run.epochs_logged, run.config.epochs);
    const char* state = run.state == RunState::finished    ? "finished"
                        : run.state == RunState::resumable ? "resume"
                                                           : "new";
    // An offline run steps no environment while it learns: its cost is its gradient updates.
    const bool offline = is_offline(run.config.alg);
    const long long updates = static_cast<long long>(run.config.epochs) * run.config.offline.updates_per_epoch;
    std::snprintf(line, sizeof line, "%-9s %5d/%-5d %15s  ", state, epochs_done, run.config.epochs,
                  offline ? (format_count(updates) + " upd").c_str() : format_count(run.training_steps()).c_str());
    text += line + run.dir.string() + "\n";
    if (offline) {
      offline_updates += updates;
      if (run.state != RunState::finished) {
        offline_updates_left += updates - static_cast<long long>(epochs_done) * run.config.offline.updates_per_epoch;
      }
    } else {
      total += run.training_steps();
      logged += run.steps_logged();
    }
    if (run.state != RunState::finished) evaluation += run.evaluation_steps();
    ++counts[static_cast<int>(run.state)];
    configurations.insert(run.run.relative_dir().parent_path().string());
  }
  text += std::string("\n") + std::to_string(plan.runs.size()) + " runs of " + std::to_string(configurations.size()) +
          " configurations: " + std::to_string(counts[static_cast<int>(RunState::finished)]) +
          " finished, " + std::to_string(counts[static_cast<int>(RunState::resumable)]) + " to resume, " +
          std::to_string(counts[static_cast<int>(RunState::fresh)]) + " new\n";
  text += "cost: " + format_count(total) + " env steps of training in all, " + format_count(total - logged) +
          " still to run, plus at most " + format_count(evaluation) + " evaluation steps\n";
  if (offline_updates > 0) {
    text += "offline runs (upd): " + format_count(offline_updates) + " gradient updates in all, " +
            format_count(offline_updates_left) + " still to run, no env step while learning\n";
  }
  return text;
}

}  // namespace bsg::experiments
