// The layout of a sweep directory (written by `bsg sweep`, read by
// `bsg table` and scripts/plot_curves.py):
//
//   <sweep>/grid.yaml          a copy of the grid file the sweep ran
//          /sweep_runs.csv     the manifest: every run the grid asks for
//                              (env_id, alg, config, seed, run_dir), so that
//                              runs not yet finished show as missing
//          /sweep_events.csv   one line per scheduling event (time, event,
//                              run_dir, detail): start, resume, done, failed
//          /table1.md, table1.csv, table1.tex, configurations.csv
//                              written by `bsg table`
//          /<env_id>/<alg>/<config>/seed=<seed>/   one run directory each
//                 run.yaml     the run's resolved configuration, written
//                              before it starts: `bsg train run.yaml --out .`
//                              reproduces it by hand
//                 train.log    the output of `bsg train`
//                 train.lock   flock()ed by the `bsg train` child while it runs
//                 + the trainer's files (algos/training/run_directory.h)
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "experiments/grid_expansion.h"

namespace bsg::experiments {

inline constexpr const char* kSweepGridCopyName = "grid.yaml";
inline constexpr const char* kSweepManifestName = "sweep_runs.csv";
inline constexpr const char* kSweepEventsName = "sweep_events.csv";
inline constexpr const char* kSweepRunFileName = "run.yaml";
inline constexpr const char* kSweepRunLogName = "train.log";

// Writes <sweep_dir>/sweep_runs.csv (atomically, replacing an older one).
void write_sweep_manifest(const std::filesystem::path& sweep_dir, const std::vector<GridRun>& runs);

// The runs of <sweep_dir>/sweep_runs.csv (set_arguments left empty); an empty
// list if the file does not exist. Throws std::runtime_error naming the file
// and line if it is malformed.
std::vector<GridRun> read_sweep_manifest(const std::filesystem::path& sweep_dir);

}  // namespace bsg::experiments
