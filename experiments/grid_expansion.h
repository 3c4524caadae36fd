// Expanding a grid (grid_file.h) into its runs: for each environment, for each
// algorithm, for each point of the algorithm's axes (Cartesian product, first
// axis outermost), for each seed - the loop order of the original benchmark
// driver (docs/reproducing.md#grids). Unlike the original, whose seed counter runs on across
// configurations, every configuration uses the grid's own seed list, so that
// configurations are compared on the same seeds.
//
// A run's directory, relative to the sweep's output directory, names its
// settings: <env_id>/<alg>/<axis=value,...>/seed=<seed>, with "default" for
// an algorithm without axes, e.g.
//   SafetyBallCircle-v0/lag-trpo/target_kl=0.001,lambda_lr=0.01/seed=0
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "common/run_config.h"
#include "experiments/grid_file.h"

namespace bsg::experiments {

struct GridRun {
  std::string env_id;
  Algorithm alg = Algorithm::trpo;
  std::string config_name;  // "target_kl=0.001,lambda_lr=0.01" or "default"
  std::int64_t seed = 0;
  // `--set` arguments that, over configs/, give this run's configuration:
  // env_id, alg, seed, the grid's fixed settings, the algorithm's, its axes.
  std::vector<std::string> set_arguments;

  std::filesystem::path relative_dir() const;
};

// The name of the configuration directory for an algorithm without axes.
inline constexpr const char* kDefaultConfigName = "default";

// Number of configurations of one algorithm: the product of its axis sizes.
std::size_t configuration_count(const AlgorithmGrid& algorithm);

// All runs, in the order above; size = envs x sum over algorithms of
// configuration_count x seeds.
std::vector<GridRun> expand_grid(const GridSpec& grid);

// The run's resolved configuration (configs/algorithms <- configs/envs <-
// the set arguments). Throws ConfigError naming the grid file and the run.
RunConfig resolve_grid_run(const GridRun& run, const std::filesystem::path& configs_dir,
                           const std::string& grid_source_name);

}  // namespace bsg::experiments
