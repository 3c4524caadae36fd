// Writing a resolved RunConfig as YAML (into a run directory, as a sweep's run file, or for
// `bsg train --print-config`) and reading it back (to resume a run) with the
// same validation as the configs/ files. The text lists exactly the keys that
// apply to the config's algorithm, in schema order, each with its description
// as a comment.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "common/run_config.h"

namespace bsg {

// The text of a run directory's config.yaml and of a checkpoint's header. Keys added after run
// directories existed are left out at the value those directories imply (tensorboard on,
// joint_control off, multiplier_schedule epoch), so that an old run's text stays the same.
std::string to_yaml(const RunConfig& config);

// The same config as a run file that names every key: layered over the algorithm and environment
// files (`bsg train FILE`, a sweep's run.yaml), it resolves to `config` whatever their defaults.
// to_yaml's text would not: sac-lag.yaml's multiplier_schedule: update_round would replace the
// epoch schedule that to_yaml leaves unsaid.
std::string to_run_file_yaml(const RunConfig& config);

// Writes to_yaml(config) to `path` (overwriting); throws ConfigError naming
// the path if it cannot be written.
void write_run_config(const RunConfig& config, const std::filesystem::path& path);

// Parses a complete resolved config: env_id, alg and every key that applies
// to alg must be present; unknown keys, keys of other algorithms, wrong types
// and out-of-range values are errors naming `source_name` and the line. If
// `valid_env_ids` is non-empty, env_id must be one of them.
RunConfig run_config_from_yaml(std::string_view yaml_text, const std::string& source_name,
                               const std::vector<std::string>& valid_env_ids = {});

// run_config_from_yaml on a file's contents (missing or malformed files are
// errors naming the path).
RunConfig load_resolved_run_config(const std::filesystem::path& path,
                                   const std::vector<std::string>& valid_env_ids = {});

}  // namespace bsg
