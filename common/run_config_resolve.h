// Resolving a run's configuration from the configs directory:
//
//   configs/algorithms/<alg>.yaml  <-  configs/envs/<env_id>.yaml
//                                  <-  the run file  <-  --set key=value ...
//
// (later layers win). The run file (or --set) names `env_id` and `alg`; the
// algorithm and environment files are found from them. Every key that
// applies to the algorithm must be set by some layer; seed and log_dir fall
// back to RunConfig's defaults (0, "runs").
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "common/config_entries.h"
#include "common/run_config.h"
#include "common/run_config_checks.h"

namespace bsg {

struct RunConfigRequest {
  std::filesystem::path configs_dir;       // holds algorithms/ and envs/ (common/configs_location.h finds it)
  std::filesystem::path run_file;          // empty: no run file (--set names env_id, alg)
  std::vector<std::string> set_arguments;  // "key=value", applied last, in order
  // Valid environment ids (e.g. from the environment registry). Empty: the
  // ids that have a file configs_dir/envs/<id>.yaml. An id listed here but
  // without a file has no environment layer; the run file must then set
  // cost_limit, epochs, steps_per_epoch and max_ep_len.
  std::vector<std::string> valid_env_ids;
  // In place of a run file (run_file empty): its entries, built elsewhere (bsg.train's dict), and
  // how messages name them (e.g. "config dict"); empty: none.
  std::vector<ConfigEntry> run_entries;
  std::string run_entries_name;
  std::vector<ConfigEntry> set_entries;  // built elsewhere (bsg.train's keywords), applied after set_arguments
};

struct ResolvedRunConfig {
  RunConfig config;
  ConfigOrigins origins;  // where each key's value came from
};

std::filesystem::path algorithm_config_path(const std::filesystem::path& configs_dir,
                                            Algorithm alg);
std::filesystem::path environment_config_path(const std::filesystem::path& configs_dir,
                                              const std::string& env_id);

// Sorted ids of the environment files configs_dir/envs/*.yaml.
std::vector<std::string> list_config_env_ids(const std::filesystem::path& configs_dir);

// Throws ConfigError (key, value, file:line or --set argument) on any error.
ResolvedRunConfig resolve_run_config(const RunConfigRequest& request);

}  // namespace bsg
