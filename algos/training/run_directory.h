// The layout of a run directory (design.md "Experiments", docs/reproducing.md#grids, #run-directory):
//
//   <run dir>/config.yaml        the resolved configuration (run_config_yaml.h)
//            /progress.csv       one row per epoch (epoch_log.h)
//            /checkpoint.bin     the latest checkpoint (training_checkpoint.h),
//                                replaced atomically at every save
//            /returns.csv        evaluation: J per episode, one per line
//            /costs.csv          evaluation: H per episode, one per line
//            /evaluation.json    evaluation summary: J, H, episodes, mean length
//            /build.txt          the build that started the run (common/build_identity.h)
//
// The default directory is <log_dir>/<env_id>/<alg>/seed_<seed, 5 digits>.
#pragma once

#include <filesystem>

#include "common/run_config.h"

namespace bsg::algos {

struct RunDirectory {
  explicit RunDirectory(std::filesystem::path root) : root(std::move(root)) {}

  std::filesystem::path root;
  std::filesystem::path config() const { return root / "config.yaml"; }
  std::filesystem::path progress() const { return root / "progress.csv"; }
  std::filesystem::path checkpoint() const { return root / "checkpoint.bin"; }
  std::filesystem::path returns() const { return root / "returns.csv"; }
  std::filesystem::path costs() const { return root / "costs.csv"; }
  std::filesystem::path evaluation() const { return root / "evaluation.json"; }
  std::filesystem::path build() const { return root / "build.txt"; }
};

// <log_dir>/<env_id>/<alg>/seed_00042
std::filesystem::path default_run_directory(const RunConfig& config);

// Throws std::runtime_error naming the directory unless it holds config.yaml
// and checkpoint.bin (the two files resume and eval need).
void check_is_run_directory(const RunDirectory& directory);

// Creates the directory for a new run; throws std::runtime_error naming it if
// it already holds a run (a checkpoint or progress.csv): resume it or choose
// another --out.
void prepare_new_run_directory(const RunDirectory& directory);

}  // namespace bsg::algos
