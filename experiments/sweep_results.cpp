#include "experiments/sweep_results.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>

#include "algos/training/run_directory.h"
#include "common/run_config_yaml.h"
#include "experiments/grid_file.h"
#include "experiments/run_results.h"
#include "experiments/sweep_manifest.h"

namespace bsg::experiments {

namespace {

struct RunSlot {
  std::int64_t seed = 0;
  std::filesystem::path run_dir;
};

struct ConfigurationSlots {
  ConfigurationResults results;
  std::vector<RunSlot> runs;
};

// config.yaml (the trainer's) or run.yaml (the sweep's), whichever exists.
std::optional<RunConfig> read_run_directory_config(const std::filesystem::path& run_dir) {
  std::error_code error;
  for (const std::filesystem::path& file :
       {algos::RunDirectory(run_dir).config(), run_dir / kSweepRunFileName}) {
    if (std::filesystem::is_regular_file(file, error)) return load_resolved_run_config(file);
  }
  return std::nullopt;
}

// Whether a run uses the PID multiplier (a Table 1 column of its own).
bool uses_pid_multiplier(const RunConfig& config) {
  return has_lagrange_multiplier(config.alg) && config.multiplier.lambda_optimizer == LambdaOptimizer::pid;
}

// The Table 1 column flags of a configuration.
struct ColumnFlags {
  bool pid_multiplier = false;
  bool corrected_learner = false;
};

ColumnFlags column_flags(const RunConfig& config) {
  return {uses_pid_multiplier(config), config.learner == Learner::corrected};
}

void set_column_flags(ConfigurationResults& results, ColumnFlags flags) {
  results.pid_multiplier = flags.pid_multiplier;
  results.corrected_learner = flags.corrected_learner;
}

// For configurations none of whose runs has a configuration file yet (not
// started): whether the sweep's grid copy sets lambda_optimizer PID and
// learner corrected for it, by configuration directory. Empty without a grid copy.
std::map<std::string, ColumnFlags> column_flags_of_grid_copy(const std::filesystem::path& sweep_dir) {
  std::map<std::string, ColumnFlags> flags;
  std::error_code error;
  const std::filesystem::path grid_copy = sweep_dir / kSweepGridCopyName;
  if (!std::filesystem::is_regular_file(grid_copy, error)) return flags;
  for (const GridRun& run : expand_grid(load_grid_file(grid_copy))) {
    ColumnFlags run_flags;  // the last setting wins, as with --set
    for (const std::string& setting : run.set_arguments) {
      if (setting.starts_with("lambda_optimizer=")) run_flags.pid_multiplier = setting == "lambda_optimizer=PID";
      if (setting.starts_with("learner=")) run_flags.corrected_learner = setting == "learner=corrected";
    }
    flags[run.relative_dir().parent_path().generic_string()] = run_flags;
  }
  return flags;
}

bool is_run_directory(const std::filesystem::path& dir) {
  std::error_code error;
  return std::filesystem::is_regular_file(algos::RunDirectory(dir).config(), error) ||
         std::filesystem::is_regular_file(dir / kSweepRunFileName, error) ||
         std::filesystem::is_regular_file(algos::RunDirectory(dir).evaluation(), error);
}

}  // namespace

std::vector<ConfigurationResults> load_sweep_results(const std::filesystem::path& sweep_dir,
                                                     bool with_episode_returns) {
  std::error_code error;
  if (!std::filesystem::is_directory(sweep_dir, error)) {
    throw std::runtime_error("sweep directory " + sweep_dir.string() + " does not exist");
  }
  std::vector<std::string> order;  // configuration directories, first seen first
  std::map<std::string, ConfigurationSlots> configurations;
  auto slots_for = [&](const std::string& config_dir) -> ConfigurationSlots& {
    auto [it, inserted] = configurations.try_emplace(config_dir);
    if (inserted) {
      order.push_back(config_dir);
      it->second.results.cost_limit = std::numeric_limits<double>::quiet_NaN();
    }
    return it->second;
  };

  // 1. The runs the grid asks for.
  for (const GridRun& run : read_sweep_manifest(sweep_dir)) {
    const std::filesystem::path relative = run.relative_dir();
    ConfigurationSlots& slots = slots_for(relative.parent_path().generic_string());
    slots.results.env_id = run.env_id;
    slots.results.alg = run.alg;
    slots.results.config_name = run.config_name;
    slots.runs.push_back({run.seed, sweep_dir / relative});
  }

  // 2. Run directories not in the manifest.
  std::map<std::string, bool> known;
  for (const auto& [name, slots] : configurations) {
    for (const RunSlot& run : slots.runs) known[run.run_dir.lexically_normal().generic_string()] = true;
  }
  std::vector<std::filesystem::path> extra;
  for (auto it = std::filesystem::recursive_directory_iterator(sweep_dir, error);
       !error && it != std::filesystem::recursive_directory_iterator(); it.increment(error)) {
    if (!it->is_directory(error) || !is_run_directory(it->path())) continue;
    it.disable_recursion_pending();
    if (!known.count(it->path().lexically_normal().generic_string())) extra.push_back(it->path());
  }
  std::sort(extra.begin(), extra.end());
  for (const std::filesystem::path& run_dir : extra) {
    const std::optional<RunConfig> config = read_run_directory_config(run_dir);
    if (!config) {
      throw std::runtime_error(run_dir.string() + ": a finished run without config.yaml or " +
                               kSweepRunFileName + "; cannot tell its environment and algorithm");
    }
    const std::filesystem::path relative = std::filesystem::relative(run_dir, sweep_dir);
    ConfigurationSlots& slots = slots_for(relative.parent_path().generic_string());
    slots.results.env_id = config->env_id;
    slots.results.alg = config->alg;
    set_column_flags(slots.results, column_flags(*config));
    slots.results.config_name = run_dir.parent_path().filename().string();
    slots.runs.push_back({config->seed, run_dir});
  }
  if (order.empty()) {
    throw std::runtime_error("no runs found in " + sweep_dir.string() + " (no " + kSweepManifestName +
                             " and no run directory below it)");
  }

  // 3. The finished runs' evaluations; d, the multiplier rule and the learner
  // from the first run with a configuration file, else (not started) from the grid copy.
  const std::map<std::string, ColumnFlags> grid_flags = column_flags_of_grid_copy(sweep_dir);
  std::vector<ConfigurationResults> results;
  for (const std::string& name : order) {
    ConfigurationSlots& slots = configurations[name];
    ConfigurationResults& config = slots.results;
    config.seeds_expected = slots.runs.size();
    config.config_dir = name;
    if (const auto found = grid_flags.find(name); found != grid_flags.end()) set_column_flags(config, found->second);
    for (const RunSlot& run : slots.runs) {
      const algos::RunDirectory directory(run.run_dir);
      if (std::isnan(config.cost_limit) && is_run_directory(run.run_dir)) {
        if (const std::optional<RunConfig> run_config = read_run_directory_config(run.run_dir)) {
          config.cost_limit = run_config->cost_limit;
          for (const ConstraintConfig& constraint : run_config->constraints) {
            config.constraint_limits.push_back(constraint.limit);
          }
          set_column_flags(config, column_flags(*run_config));
        }
      }
      const std::optional<RecordedEvaluation> evaluation = read_run_evaluation(directory);
      // A run trained with eval_episodes: 0 is finished but has no J or H.
      if (!evaluation || evaluation->episodes == 0) continue;
      SeedResult seed{run.seed, evaluation->mean_return, evaluation->mean_cost, {}, evaluation->cost_rate,
                      config.constraint_limits.empty() ? std::vector<double>{} : evaluation->constraint_costs,
                      run.run_dir};
      if (with_episode_returns) seed.episode_returns = read_value_per_line(directory.returns());
      config.seeds.push_back(std::move(seed));
    }
    results.push_back(std::move(config));
  }
  return results;
}

}  // namespace bsg::experiments
