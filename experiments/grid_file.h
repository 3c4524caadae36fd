// A grid file (configs/grids/*.yaml): the experiment a sweep runs. It names
// the environments, the seeds, settings fixed for every run, and for each
// algorithm the axes to sweep; the sweep is the Cartesian product
// envs x algorithms x (their axes) x seeds (grid_expansion.h).
//
//   description: free text                      (optional)
//   envs: [SafetyBallCircle-v0, ...]            (required, distinct ids)
//   seeds: [0, 1, 2, 3]                         (required, distinct, >= 0)
//   fixed: {epochs: 3, ...}                     (optional; applied to every
//                                                algorithm the key applies to)
//   algorithms:                                 (required, at least one)
//     lag-trpo:
//       fixed: {lambda_optimizer: SGD}          (optional)
//       axes:                                   (optional; empty: one config)
//         target_kl: [0.0001, 0.001, 0.01]      (outer axis first)
//         lambda_lr: [0.001, 0.01, 0.1]
//
// Keys under `fixed` and `axes` are run-configuration keys (configs/README.md)
// other than env_id, alg, seed and log_dir, which the sweep sets itself. Every
// value is type- and range-checked here; errors name the file, line and key.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "common/run_config.h"

namespace bsg::experiments {

// One `key: value` of a grid: the value as `--set` text (key=value_text) and
// as a directory-name fragment (the value as written; lists joined by 'x').
struct GridSetting {
  std::string key;
  std::string value_text;  // YAML text, e.g. "0.001", "[32, 32]"
  std::string name_text;   // e.g. "0.001", "32x32"
  std::string origin;      // "file:line:column" of the value
};

struct GridAxis {
  std::string key;
  std::vector<GridSetting> values;  // in file order
};

struct AlgorithmGrid {
  Algorithm alg = Algorithm::trpo;
  std::vector<GridSetting> fixed;
  std::vector<GridAxis> axes;  // in file order: the first is the outermost loop
};

struct GridSpec {
  std::string source_name;  // the file, for messages
  std::string description;
  std::vector<std::string> env_ids;
  std::vector<std::int64_t> seeds;
  std::vector<GridSetting> fixed;        // for every algorithm the key applies to
  std::vector<AlgorithmGrid> algorithms;  // in file order
};

// Parses grid text; throws ConfigError naming `source_name`, the line and the
// key at fault (unknown keys, wrong shapes, bad or duplicate values).
GridSpec parse_grid(std::string_view yaml_text, const std::string& source_name);

// parse_grid on a file (a missing or malformed file is an error naming it).
GridSpec load_grid_file(const std::filesystem::path& path);

}  // namespace bsg::experiments
