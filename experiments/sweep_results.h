// Collecting a sweep directory's results (layout in experiments/sweep_manifest.h)
// for the selection rule: one ConfigurationResults per configuration
// directory <env_id>/<alg>/<config>, with the runs the manifest expects and
// the finished ones among them (evaluation.json). Run directories found below
// the sweep directory but not in the manifest (or when there is none, e.g.
// hand-made ones) are added; their configuration is read from config.yaml
// (or run.yaml), and their configuration name is their parent's name.
// Whether a configuration uses the PID multiplier or the corrected learner
// (Table 1 columns of their own) comes from its first run's configuration file or, before any has started,
// from the sweep's grid copy (grid.yaml).
#pragma once

#include <filesystem>
#include <vector>

#include "experiments/selection.h"

namespace bsg::experiments {

// In manifest order, then the others sorted by path. With
// `with_episode_returns`, each finished seed's returns.csv is read too.
// Throws std::runtime_error naming the file at fault, or the directory if it
// does not exist or holds no run at all.
std::vector<ConfigurationResults> load_sweep_results(const std::filesystem::path& sweep_dir,
                                                     bool with_episode_returns);

}  // namespace bsg::experiments
