#include "experiments/grid_expansion.h"

#include "algos/training/run_start.h"
#include "common/config_error.h"
#include "common/run_config_resolve.h"
#include "common/run_config_schema.h"

namespace bsg::experiments {

std::filesystem::path GridRun::relative_dir() const {
  return std::filesystem::path(env_id) / std::string(to_string(alg)) / config_name /
         ("seed=" + std::to_string(seed));
}

std::size_t configuration_count(const AlgorithmGrid& algorithm) {
  std::size_t count = 1;
  for (const GridAxis& axis : algorithm.axes) count *= axis.values.size();
  return count;
}

std::vector<GridRun> expand_grid(const GridSpec& grid) {
  std::vector<GridRun> runs;
  for (const std::string& env_id : grid.env_ids) {
    for (const AlgorithmGrid& algorithm : grid.algorithms) {
      const std::size_t configs = configuration_count(algorithm);
      for (std::size_t point = 0; point < configs; ++point) {
        // Mixed-radix digits of `point`, the last axis varying fastest.
        std::vector<const GridSetting*> chosen(algorithm.axes.size());
        std::size_t rest = point;
        for (std::size_t a = algorithm.axes.size(); a-- > 0;) {
          const std::vector<GridSetting>& values = algorithm.axes[a].values;
          chosen[a] = &values[rest % values.size()];
          rest /= values.size();
        }
        std::string config_name;
        for (const GridSetting* setting : chosen) {
          config_name += (config_name.empty() ? "" : ",") + setting->key + "=" + setting->name_text;
        }
        if (config_name.empty()) config_name = kDefaultConfigName;

        for (const std::int64_t seed : grid.seeds) {
          GridRun run;
          run.env_id = env_id;
          run.alg = algorithm.alg;
          run.config_name = config_name;
          run.seed = seed;
          run.set_arguments = {"env_id=" + env_id, "alg=" + std::string(to_string(algorithm.alg)),
                               "seed=" + std::to_string(seed)};
          for (const GridSetting& setting : grid.fixed) {
            if (find_config_key(setting.key)->applies_to(algorithm.alg)) {
              run.set_arguments.push_back(setting.key + "=" + setting.value_text);
            }
          }
          for (const GridSetting& setting : algorithm.fixed) {
            run.set_arguments.push_back(setting.key + "=" + setting.value_text);
          }
          for (const GridSetting* setting : chosen) {
            run.set_arguments.push_back(setting->key + "=" + setting->value_text);
          }
          runs.push_back(std::move(run));
        }
      }
    }
  }
  return runs;
}

RunConfig resolve_grid_run(const GridRun& run, const std::filesystem::path& configs_dir,
                           const std::string& grid_source_name) {
  try {
    // Every registered id, as `bsg train` accepts: a fork id (no configs/envs/
    // file) then takes cost_limit, epochs, steps_per_epoch and max_ep_len from the grid.
    RunConfigRequest request;
    request.configs_dir = configs_dir;
    request.set_arguments = run.set_arguments;
    request.valid_env_ids = algos::training_env_ids();
    return resolve_run_config(request).config;
  } catch (const ConfigError& e) {
    throw ConfigError(grid_source_name + ": run " + run.relative_dir().string() + ": " + e.what());
  }
}

}  // namespace bsg::experiments
