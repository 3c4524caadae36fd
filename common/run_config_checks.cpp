#include "common/run_config_checks.h"

#include "common/config_error.h"
#include "common/run_config_schema.h"

namespace bsg {

namespace {
std::string origin_of(const ConfigOrigins& origins, const std::string& key) {
  const auto it = origins.find(key);
  return it == origins.end() ? std::string("default") : it->second;
}
}  // namespace

const ConfigEntry* find_last_entry(const std::vector<ConfigEntry>& entries,
                                   const std::string& key) {
  const ConfigEntry* last = nullptr;
  for (const ConfigEntry& entry : entries) {
    if (entry.key == key) last = &entry;
  }
  return last;
}

void apply_config_entries(RunConfig& config, const std::vector<ConfigEntry>& entries,
                          ConfigOrigins& origins) {
  for (const ConfigEntry& entry : entries) {
    const ConfigKey* key = find_config_key(entry.key);
    if (key == nullptr) {  // read_config_entries already rejects these
      throw ConfigError(entry.origin + ": unknown key '" + entry.key +
                        "'; valid keys: " + config_key_list());
    }
    if (!key->applies_to(config.alg)) {
      throw ConfigError(entry.origin + ": key '" + entry.key + "' does not apply to alg '" +
                        std::string(to_string(config.alg)) + "'; it is used by " +
                        key->used_by_text());
    }
    if (entry.key == "alg" || entry.key == "env_id") {
      // Chosen before the layers are applied; an overridden value must still be valid.
      RunConfig scratch;
      set_config_value(scratch, *key, entry.value, entry.origin);
      continue;
    }
    set_config_value(config, *key, entry.value, entry.origin);
    origins[entry.key] = entry.origin;
  }
}

void check_env_id(const std::string& env_id, const std::string& origin,
                  const std::vector<std::string>& valid_env_ids) {
  for (const std::string& valid : valid_env_ids) {
    if (valid == env_id) return;
  }
  std::string list;
  for (const std::string& valid : valid_env_ids) list += (list.empty() ? "" : ", ") + valid;
  throw ConfigError(origin + ": unknown env_id '" + env_id + "'; valid env ids: " +
                    (list.empty() ? std::string("(none)") : list));
}

void check_run_config_relations(const RunConfig& config, const ConfigOrigins& origins) {
  if (config.alg == Algorithm::trpo && config.constraints.size() > 1) {
    throw ConfigError(origin_of(origins, "constraints") + ": key 'constraints' lists " +
                      std::to_string(config.constraints.size()) +
                      " constraints, but alg 'trpo' ignores cost (it maximises the return alone); use lag-trpo, "
                      "pdo, cpo or pcpo, or give one constraint to judge TRPO's policy by");
  }
  if (config.max_ep_len > config.steps_per_epoch) {
    throw ConfigError("max_ep_len = " + std::to_string(config.max_ep_len) + " (" +
                      origin_of(origins, "max_ep_len") + ") exceeds steps_per_epoch = " +
                      std::to_string(config.steps_per_epoch) + " (" +
                      origin_of(origins, "steps_per_epoch") +
                      "): every epoch must complete at least one episode");
  }
}

void check_run_config_for_ranks(const RunConfig& config, int num_ranks) {
  if (num_ranks < 1) {
    throw ConfigError("number of MPI ranks must be at least 1, got " + std::to_string(num_ranks));
  }
  const std::string ranks = std::to_string(num_ranks);
  if (config.steps_per_epoch % num_ranks != 0) {
    throw ConfigError("steps_per_epoch = " + std::to_string(config.steps_per_epoch) +
                      " is not divisible by the " + ranks + " MPI ranks");
  }
  const int local_steps = config.steps_per_epoch / num_ranks;
  if (config.max_ep_len > local_steps) {
    throw ConfigError("max_ep_len = " + std::to_string(config.max_ep_len) +
                      " exceeds the local steps per rank steps_per_epoch / ranks = " +
                      std::to_string(local_steps) + " with " + ranks +
                      " ranks: reduce the ranks or increase steps_per_epoch");
  }
  const int minibatch = local_steps / config.num_mini_batches;
  if (minibatch < 16) {
    throw ConfigError("value-net minibatch floor(" + std::to_string(local_steps) + " / " +
                      "num_mini_batches = " + std::to_string(config.num_mini_batches) +
                      ") = " + std::to_string(minibatch) + " is below 16 samples with " + ranks +
                      " ranks: increase steps_per_epoch or reduce num_mini_batches");
  }
}

}  // namespace bsg
