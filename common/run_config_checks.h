// Checks shared by resolving a run (run_config_resolve.h) and loading a
// resolved config back (run_config_yaml.h): applying entries to a RunConfig
// under the algorithm's key set, validating env_id, and the relations
// between keys that no single key's range can express.
#pragma once

#include <cstddef>
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
// max_ep_len <= steps_per_epoch; at most one constraint for trpo, which
// ignores cost; and bounds no single key's range states: at most
// kMaxHiddenLayers hidden layers, steps_per_epoch <= kMaxStepsPerEpoch,
// epochs <= kMaxEpochs, eval_episodes <= kMaxEvalEpisodes. Names the keys and
// their origins.
void check_run_config_relations(const RunConfig& config, const ConfigOrigins& origins);

inline constexpr std::size_t kMaxHiddenLayers = 32;
inline constexpr int kMaxStepsPerEpoch = 100'000'000;
inline constexpr int kMaxEpochs = 10'000'000;
inline constexpr int kMaxEvalEpisodes = 1'000'000;

// Bytes one rank's training holds at its peak, estimated from the arrays it
// allocates (8-byte values): about 8 copies of every network parameter
// (parameters, gradients, Adam moments, conjugate-gradient vectors, line-search
// copies), two layer activations per hidden unit over the batch
// (N = steps_per_epoch / ranks rows), the rollout buffer, and 64 MB for the
// program itself. Measured peak resident memory (docs/reproducing.md#limits):
// 319 MB for hidden_sizes [1024, 1024] and N = 4000 (estimate 384 MB), 51 MB
// for [64, 64] and N = 64000 (estimate 206 MB): it errs on the high side.
struct TrainingMemoryEstimate {
  double bytes = 0;
  double network_bytes = 0;  // the part that grows with hidden_sizes
  double batch_bytes = 0;    // the part that grows with steps_per_epoch / ranks
};
TrainingMemoryEstimate estimate_training_memory(const RunConfig& config, int observation_dim, int action_dim,
                                                int num_ranks);

// What holds a run's training data, named for messages about memory: its key
// ("steps_per_epoch = 32000"), what it is ("the rollout buffer (16000 steps per rank)"),
// its size alone ("16000 steps per rank") and what to reduce ("steps_per_epoch or run
// on more ranks"). On-policy: the rollout buffer; off-policy: the replay buffer; offline:
// the batches (the dataset itself is read whole).
struct TrainingBuffer {
  std::string key;
  std::string description;
  std::string size;
  std::string advice;
};
TrainingBuffer training_buffer(const RunConfig& config, int num_ranks);

// The memory a process can use: the smaller of physical memory and its
// address-space limit (RLIMIT_AS), and how each was found, for messages.
struct AvailableMemory {
  double bytes = 0;
  std::string description;  // "physical memory 23.4 GB, address-space limit unlimited"
};
AvailableMemory available_memory();

// Throws ConfigError naming the key that dominates the estimate
// (hidden_sizes or steps_per_epoch), the estimate and the available memory
// if the estimate exceeds it.
void check_training_memory(const RunConfig& config, int observation_dim, int action_dim, int num_ranks,
                           const AvailableMemory& available);

// "1.50 GB", "512.0 MB", "12.0 kB".
std::string format_bytes(double bytes);

// The set-up checks of docs/algorithms.md#set-up, step 2 for `num_ranks` MPI processes:
// steps_per_epoch divisible by num_ranks, max_ep_len <= local steps N, and
// value-net minibatches of at least 16 samples (floor(N / num_mini_batches)).
void check_run_config_for_ranks(const RunConfig& config, int num_ranks);

}  // namespace bsg
