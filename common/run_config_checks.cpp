#include "common/run_config_checks.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <numeric>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "common/config_error.h"
#include "common/message_text.h"
#include "common/config_scalar.h"
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
  const std::string list = comma_separated(valid_env_ids);
  throw ConfigError(origin + ": unknown env_id '" + env_id + "'; valid env ids: " +
                    (list.empty() ? std::string("(none)") : list));
}

namespace {

// Whether the family collects its batch on-policy each epoch (one rollout of steps_per_epoch steps).
bool uses_on_policy_batches(Algorithm alg) {
  switch (algorithm_info(alg).family) {
    case AlgorithmFamily::trust_region:
    case AlgorithmFamily::first_order:
    case AlgorithmFamily::multi_agent: return true;
    case AlgorithmFamily::off_policy:
    case AlgorithmFamily::offline: return false;
  }
  return false;
}

// The offline algorithms learn from `dataset:` and judge one cost against cost_limit.
void check_offline_relations(const RunConfig& config, const ConfigOrigins& origins) {
  const std::string alg(to_string(config.alg));
  if (config.offline.dataset.empty()) {
    throw ConfigError("alg '" + alg + "' learns from a dataset: set 'dataset: FILE' (an HDF5 file in DSRL's "
                      "layout, e.g. written by bsg collect) in the run file or with --set dataset=FILE");
  }
  if (config.constraints.size() > 1) {
    throw ConfigError(origin_of(origins, "constraints") + ": key 'constraints' lists " +
                      std::to_string(config.constraints.size()) + " constraints, but alg '" + alg +
                      "' judges one cost (the dataset's costs) against cost_limit");
  }
}

// Saute's budget update divides each cost by its limit (common/budget_keys.h, envs/saute_env.h).
void check_saute_budgets(const RunConfig& config, const ConfigOrigins& origins) {
  const std::string alg(to_string(config.alg));
  if (config.constraints.empty() && !(config.cost_limit > 0.0)) {
    throw ConfigError(origin_of(origins, "cost_limit") + ": key 'cost_limit' is " + format_config_real(config.cost_limit) +
                      ", but alg '" + alg + "' keeps it as a Saute budget, which must be positive");
  }
  for (std::size_t i = 0; i < config.constraints.size(); ++i) {
    if (config.constraints[i].limit > 0.0) continue;
    throw ConfigError(origin_of(origins, "constraints") + ": key 'constraints' gives constraint " +
                      std::to_string(i + 1) + " the limit " + format_config_real(config.constraints[i].limit) +
                      ", but alg '" + alg + "' keeps each limit as a Saute budget, which must be positive");
  }
}

// The multi-agent learners judge the agents' own cost against cost_limit and build the registered
// environment as it is (docs/multi_agent.md#learners).
void check_multi_agent_relations(const RunConfig& config, const ConfigOrigins& origins) {
  const std::string alg(to_string(config.alg));
  if (!config.constraints.empty()) {
    throw ConfigError(origin_of(origins, "constraints") + ": key 'constraints' is not supported by alg '" + alg +
                      "' (a multi-agent learner constrains each agent's episode cost against cost_limit)");
  }
  if (!config.env.empty()) {
    throw ConfigError(origin_of(origins, "env") + ": key 'env' is not supported by alg '" + alg +
                      "' (a multi-agent run trains on the registered description of its env_id)");
  }
}

// The on-policy algorithms that constrain their cost, as "a, b or c" (the table's order).
std::string constrained_on_policy_algorithms() {
  std::vector<std::string_view> names;
  for (const AlgorithmInfo& info : kAlgorithms) {
    if (info.constrained && uses_on_policy_batches(info.alg) && !is_multi_agent(info.alg)) names.push_back(info.name);
  }
  std::string text;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (i > 0) text += i + 1 == names.size() ? " or " : ", ";
    text += names[i];
  }
  return text;
}

}  // namespace

void check_run_config_relations(const RunConfig& config, const ConfigOrigins& origins) {
  if (ignores_cost(config.alg) && config.constraints.size() > 1) {
    const std::string alg(to_string(config.alg));
    throw ConfigError(origin_of(origins, "constraints") + ": key 'constraints' lists " +
                      std::to_string(config.constraints.size()) + " constraints, but alg '" + alg +
                      "' ignores cost (it maximises the return alone); use " + constrained_on_policy_algorithms() +
                      ", or give one constraint to judge the policy by");
  }
  if (is_offline(config.alg)) check_offline_relations(config, origins);
  if (is_multi_agent(config.alg)) check_multi_agent_relations(config, origins);
  if (keeps_saute_budgets(config.alg)) check_saute_budgets(config, origins);
  // Only an on-policy epoch must complete an episode: the off-policy loop's episodes run on across
  // epochs (check_run_config_for_ranks bounds them), the offline family steps no environment.
  if (uses_on_policy_batches(config.alg) && config.max_ep_len > config.steps_per_epoch) {
    throw ConfigError("max_ep_len = " + std::to_string(config.max_ep_len) + " (" +
                      origin_of(origins, "max_ep_len") + ") exceeds steps_per_epoch = " +
                      std::to_string(config.steps_per_epoch) + " (" +
                      origin_of(origins, "steps_per_epoch") +
                      "): every epoch must complete at least one episode");
  }
  if (config.hidden_sizes.size() > kMaxHiddenLayers) {
    throw ConfigError("hidden_sizes (" + origin_of(origins, "hidden_sizes") + ") lists " +
                      std::to_string(config.hidden_sizes.size()) + " hidden layers; at most " +
                      std::to_string(kMaxHiddenLayers) + " are allowed");
  }
  if (config.exploration_anneal_epochs > 0) {
    const std::string where = "exploration_anneal_epochs = " + std::to_string(config.exploration_anneal_epochs) +
                              " (" + origin_of(origins, "exploration_anneal_epochs") + ")";
    if (config.exploration_anneal_epochs > config.epochs) {
      throw ConfigError(where + " exceeds epochs = " + std::to_string(config.epochs) + " (" +
                        origin_of(origins, "epochs") + "): the annealing must end within the run");
    }
    if (!config.use_exploration_noise_anneal || config.first_order.learn_log_std) {
      throw ConfigError(where + " has no effect: sigma is " +
                        (config.first_order.learn_log_std ? std::string("learned (learn_log_std: true)")
                                              : std::string("fixed (use_exploration_noise_anneal: false)")) +
                        "; set it to 0 or anneal sigma");
    }
  }
  if (config.exploration_std_floor > 0.0 &&
      (!config.use_exploration_noise_anneal || config.first_order.learn_log_std)) {
    throw ConfigError("exploration_std_floor = " + format_config_real(config.exploration_std_floor) + " (" +
                      origin_of(origins, "exploration_std_floor") + ") has no effect: sigma is " +
                      (config.first_order.learn_log_std ? std::string("learned (learn_log_std: true)")
                                            : std::string("fixed (use_exploration_noise_anneal: false)")) +
                      "; set it to 0 or anneal sigma");
  }
  const auto check_at_most = [&](const char* key, long long value, long long limit) {
    if (value > limit) {
      throw ConfigError(std::string(key) + " = " + std::to_string(value) + " (" + origin_of(origins, key) +
                        ") exceeds the limit " + std::to_string(limit));
    }
  };
  check_at_most("steps_per_epoch", config.steps_per_epoch, kMaxStepsPerEpoch);
  check_at_most("epochs", config.epochs, kMaxEpochs);
  check_at_most("eval_episodes", config.eval_episodes, kMaxEvalEpisodes);
}

std::string format_bytes(double bytes) {
  const char* units[] = {"bytes", "kB", "MB", "GB", "TB", "PB"};
  int unit = 0;
  while (bytes >= 1024.0 && unit < 5) {
    bytes /= 1024.0;
    ++unit;
  }
  char text[48];
  std::snprintf(text, sizeof text, unit == 0 ? "%.0f %s" : "%.2f %s", bytes, units[unit]);
  return text;
}

TrainingMemoryEstimate estimate_training_memory(const RunConfig& config, int observation_dim, int action_dim,
                                                int num_ranks) {
  const double batch = static_cast<double>(config.steps_per_epoch) / std::max(num_ranks, 1);
  const double hidden_sum = std::accumulate(config.hidden_sizes.begin(), config.hidden_sizes.end(), 0.0);
  // Parameters of an MLP observation -> hidden_sizes -> outputs: weights and biases.
  const auto parameters = [&](double outputs) {
    double count = 0;
    double inputs = observation_dim;
    for (const int width : config.hidden_sizes) {
      count += inputs * width + width;
      inputs = width;
    }
    return count + inputs * outputs + outputs;
  };
  const double policy = parameters(action_dim) + action_dim;
  const double value = parameters(1);
  const double parameter_values = 8 * (policy + 2 * value);
  const double activation_values = 2 * batch * hidden_sum;
  // The rollout buffer: raw and normalised observations, actions, means,
  // log-probabilities, rewards, costs, values, advantages and returns.
  // Off-policy: the replay buffer instead (observations, next observations,
  // actions, reward, cost, discount and flags per transition), batch_size rows of activations.
  // Offline: batch_size rows of a batch (the dataset, read from its file, is not counted here).
  double buffer_values = 0.0;
  switch (algorithm_info(config.alg).family) {
    case AlgorithmFamily::trust_region:
    case AlgorithmFamily::first_order:
    case AlgorithmFamily::multi_agent: buffer_values = batch * (2.0 * observation_dim + 2.0 * action_dim + 12.0); break;
    case AlgorithmFamily::off_policy:
      buffer_values = static_cast<double>(config.off_policy.buffer_size) * (2.0 * observation_dim + action_dim + 4.0);
      break;
    case AlgorithmFamily::offline: buffer_values = static_cast<double>(config.off_policy.batch_size) * (observation_dim + action_dim); break;
  }
  constexpr double kProgramBytes = 64.0 * 1024 * 1024;
  TrainingMemoryEstimate estimate;
  estimate.network_bytes = 8 * (parameter_values + activation_values);
  estimate.batch_bytes = 8 * buffer_values + kProgramBytes;
  estimate.bytes = estimate.network_bytes + estimate.batch_bytes;
  return estimate;
}

AvailableMemory available_memory() {
  AvailableMemory available;
  const long pages = ::sysconf(_SC_PHYS_PAGES);
  const long page_size = ::sysconf(_SC_PAGE_SIZE);
  const double physical = pages > 0 && page_size > 0 ? static_cast<double>(pages) * page_size : 0.0;
  available.bytes = physical;
  available.description = "physical memory " + (physical > 0 ? format_bytes(physical) : std::string("unknown"));
  rlimit limit{};
  if (::getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY) {
    const double address_space = static_cast<double>(limit.rlim_cur);
    available.description += ", address-space limit (ulimit -v) " + format_bytes(address_space);
    if (available.bytes <= 0 || address_space < available.bytes) available.bytes = address_space;
  } else {
    available.description += ", address-space limit unlimited";
  }
  return available;
}

TrainingBuffer training_buffer(const RunConfig& config, int num_ranks) {
  const int ranks = std::max(num_ranks, 1);
  switch (algorithm_info(config.alg).family) {
    case AlgorithmFamily::trust_region:
    case AlgorithmFamily::first_order:
    case AlgorithmFamily::multi_agent:
      return {"steps_per_epoch = " + std::to_string(config.steps_per_epoch),
              "the rollout buffer (" + std::to_string(config.steps_per_epoch / ranks) + " steps per rank)",
              std::to_string(config.steps_per_epoch / ranks) + " steps per rank",
              "steps_per_epoch or run on more ranks"};
    case AlgorithmFamily::off_policy:
      return {"buffer_size = " + std::to_string(config.off_policy.buffer_size),
              "the replay buffer (" + std::to_string(config.off_policy.buffer_size) + " transitions per rank)",
              "a replay buffer of " + std::to_string(config.off_policy.buffer_size) + " transitions per rank",
              "buffer_size"};
    case AlgorithmFamily::offline:
      return {"batch_size = " + std::to_string(config.off_policy.batch_size),
              "the batches (" + std::to_string(config.off_policy.batch_size) + " rows)",
              "batches of " + std::to_string(config.off_policy.batch_size) + " rows",
              "batch_size"};
  }
  throw std::invalid_argument("training_buffer: unknown family of alg " + std::string(to_string(config.alg)));
}

void check_training_memory(const RunConfig& config, int observation_dim, int action_dim, int num_ranks,
                           const AvailableMemory& available) {
  const TrainingMemoryEstimate estimate = estimate_training_memory(config, observation_dim, action_dim, num_ranks);
  if (available.bytes <= 0 || estimate.bytes <= available.bytes) return;
  std::string hidden;
  for (const int width : config.hidden_sizes) hidden += (hidden.empty() ? "" : ", ") + std::to_string(width);
  const bool network = estimate.network_bytes >= estimate.batch_bytes;
  const TrainingBuffer buffer = training_buffer(config, num_ranks);
  throw ConfigError((network ? "hidden_sizes = [" + hidden + "]" : buffer.key) + " needs an estimated " +
                    format_bytes(estimate.bytes) + " per rank (" + buffer.size + ", hidden_sizes [" + hidden +
                    "]), more than the " + format_bytes(available.bytes) + " available (the smaller of " +
                    available.description + "): reduce " + (network ? "hidden_sizes" : buffer.advice));
}

namespace {

// Every rank would take the same gradient steps on the same dataset: there is nothing to split.
void check_offline_ranks(const RunConfig& config, const std::string& ranks, int num_ranks) {
  if (num_ranks > 1) {
    throw ConfigError("alg '" + std::string(to_string(config.alg)) + "' trains on one rank, not " + ranks +
                      ": an offline run learns from one dataset in memory and steps no environment, so there "
                      "is no data to split over ranks; run it without mpirun (or with -np 1)");
  }
}

void check_steps_divide(const RunConfig& config, const std::string& ranks, int num_ranks) {
  if (config.steps_per_epoch % num_ranks != 0) {
    throw ConfigError("steps_per_epoch = " + std::to_string(config.steps_per_epoch) +
                      " is not divisible by the " + ranks + " MPI ranks");
  }
}

// Each rank's batch must complete an episode and fill the value nets' minibatches.
void check_on_policy_ranks(const RunConfig& config, const std::string& ranks, int local_steps) {
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

// The off-policy loop steps num_envs environments in turn and has no value-net minibatches.
void check_off_policy_ranks(const RunConfig& config, const std::string& ranks, int local_steps) {
  const int num_envs = config.off_policy.num_envs;
  if (local_steps % num_envs != 0) {
    throw ConfigError("steps_per_epoch / ranks = " + std::to_string(local_steps) + " with " + ranks +
                      " ranks is not a multiple of num_envs = " + std::to_string(num_envs));
  }
  // Episodes run on across epochs but a checkpoint cuts them (docs/algorithms.md#off-policy-checkpoints),
  // so each environment needs max_ep_len steps between checkpoints for an episode to end.
  const long long steps_between_checkpoints = static_cast<long long>(config.save_freq) * (local_steps / num_envs);
  if (steps_between_checkpoints < config.max_ep_len) {
    throw ConfigError("each environment steps save_freq * steps_per_epoch / (ranks * num_envs) = " +
                      std::to_string(config.save_freq) + " * " + std::to_string(config.steps_per_epoch) + " / (" +
                      ranks + " * " + std::to_string(num_envs) + ") = " + std::to_string(steps_between_checkpoints) +
                      " steps between checkpoints, which cut episodes; that is fewer than max_ep_len = " +
                      std::to_string(config.max_ep_len) +
                      ", so no episode would end: raise save_freq or steps_per_epoch, or lower num_envs");
  }
}

}  // namespace

void check_run_config_for_ranks(const RunConfig& config, int num_ranks) {
  if (num_ranks < 1) {
    throw ConfigError("number of MPI ranks must be at least 1, got " + std::to_string(num_ranks));
  }
  const std::string ranks = std::to_string(num_ranks);
  switch (algorithm_info(config.alg).family) {
    case AlgorithmFamily::trust_region:
    case AlgorithmFamily::first_order:
    case AlgorithmFamily::multi_agent:
      check_steps_divide(config, ranks, num_ranks);
      check_on_policy_ranks(config, ranks, config.steps_per_epoch / num_ranks);
      return;
    case AlgorithmFamily::off_policy:
      check_steps_divide(config, ranks, num_ranks);
      check_off_policy_ranks(config, ranks, config.steps_per_epoch / num_ranks);
      return;
    case AlgorithmFamily::offline: check_offline_ranks(config, ranks, num_ranks); return;
  }
}

}  // namespace bsg
