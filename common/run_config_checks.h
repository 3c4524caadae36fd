// Checks shared by resolving a run (run_config_resolve.h) and loading a
// resolved config back (run_config_yaml.h): applying entries to a RunConfig
// under the algorithm's key set, validating env_id, and the relations
// between keys that no single key's range can express.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "common/config_entries.h"
#include "common/run_config.h"

namespace bsg {

// key -> where its value came from ("path:line:col", "--set k=v", "default").
using ConfigOrigins = std::map<std::string, std::string>;

// The last entry for `key` in `entries`, or nullptr.
const ConfigEntry* find_last_entry(const std::vector<ConfigEntry>& entries, const std::string& key);

// Stores every entry in `config` (type and range checked) and records its
// origin. `config.alg` and `config.env_id` must already be chosen: entries for
// them are only type-checked, not stored. A key that does not apply to the
// algorithm (e.g. lambda_lr for cpo) is an error naming the algorithms it
// applies to.
void apply_config_entries(RunConfig& config, const std::vector<ConfigEntry>& entries,
                          ConfigOrigins& origins);

// Throws ConfigError listing `valid_env_ids` unless `env_id` is among them.
void check_env_id(const std::string& env_id, const std::string& origin,
                  const std::vector<std::string>& valid_env_ids);

// Relations between keys that hold for any number of ranks:
// max_ep_len <= steps_per_epoch (naming both keys and their origins); at
// most one constraint for trpo, which ignores cost.
void check_run_config_relations(const RunConfig& config, const ConfigOrigins& origins);

// The set-up checks of docs/algorithms.md#set-up, step 2 for `num_ranks` MPI processes:
// steps_per_epoch divisible by num_ranks, max_ep_len <= local steps N, and
// value-net minibatches of at least 16 samples (floor(N / num_mini_batches)).
void check_run_config_for_ranks(const RunConfig& config, int num_ranks);

}  // namespace bsg
