#include "common/run_config_resolve.h"

#include <algorithm>
#include <system_error>

#include "common/config_entries.h"
#include "common/config_error.h"
#include "common/message_text.h"
#include "common/learner_preset.h"
#include "common/run_config_schema.h"

namespace bsg {

namespace {

// env_id and alg choose the other layers, so only the run file and --set may
// name them; seed and log_dir describe the run, not the algorithm or task.
void reject_run_keys(const std::vector<ConfigEntry>& entries, const char* layer_name) {
  for (const ConfigEntry& entry : entries) {
    const ConfigKey* key = find_config_key(entry.key);
    if (key != nullptr && key->default_source == ConfigLayer::run) {
      throw ConfigError(entry.origin + ": key '" + entry.key + "' cannot be set in " +
                        layer_name + " file; set it in the run file or with --set");
    }
  }
}

// The value of env_id or alg: the last --set, else the run file.
const ConfigEntry& choosing_entry(const std::vector<ConfigEntry>& run_entries,
                                  const std::vector<ConfigEntry>& set_entries,
                                  const std::string& key, const RunConfigRequest& request,
                                  const std::string& valid_values) {
  if (const ConfigEntry* entry = find_last_entry(set_entries, key)) return *entry;
  if (const ConfigEntry* entry = find_last_entry(run_entries, key)) return *entry;
  const std::string where = !request.run_file.empty() ? "the run file " + request.run_file.string() + " does not"
                            : request.run_entries_name.empty() ? std::string("no run file was given to")
                                                               : "the " + request.run_entries_name + " does not";
  throw ConfigError("no '" + key + "' given (" + where + " name it); set it in the run file or " +
                    "with --set " + key + "=...; valid values: " + valid_values);
}

// The pid_* keys change nothing unless lambda_optimizer is PID, and lambda_lr
// nothing when it is. A value of one of them that differs from the algorithm
// file's while it has no effect is a mistake to report, not a setting to
// ignore (equal values are fine: a resolved config lists every key).
void reject_ineffective_multiplier_keys(const RunConfig& config, const RunConfig& algorithm_defaults,
                                        const ConfigOrigins& origins) {
  const bool pid = config.multiplier.lambda_optimizer == LambdaOptimizer::pid;
  for (const ConfigKey& key : run_config_schema()) {
    const bool pid_key = key.key.starts_with("pid_");
    const bool ineffective = pid ? key.key == "lambda_lr" : pid_key;
    if (!ineffective || !key.applies_to(config.alg) ||
        config_value_to_yaml(config, key) == config_value_to_yaml(algorithm_defaults, key)) {
      continue;
    }
    const std::string name(key.key);
    const auto origin = origins.find(name);
    const std::string where = origin == origins.end() ? std::string("default") : origin->second;
    if (pid_key) {
      throw ConfigError(where + ": key '" + name + "' applies only with lambda_optimizer: PID, but " +
                        "lambda_optimizer is " + std::string(to_string(config.multiplier.lambda_optimizer)) +
                        "; set lambda_optimizer: PID as well");
    }
    throw ConfigError(where + ": key 'lambda_lr' has no effect with lambda_optimizer: PID; the PID " +
                      "rule's integral gain is pid_ki");
  }
}

// A run file whose env: block names agent and task but that gives no env_id
// starts from their standard description: env_id Safety<agent><task>-v0.
std::vector<ConfigEntry> implied_env_id(const std::vector<ConfigEntry>& run_entries,
                                        const std::vector<ConfigEntry>& set_entries) {
  if (find_last_entry(set_entries, "env_id") || find_last_entry(run_entries, "env_id")) return {};
  std::string agent, task, origin;
  for (const auto* layer : {&run_entries, &set_entries}) {
    for (const ConfigEntry& entry : *layer) {
      if (entry.key != "env" || !entry.value.IsMap()) continue;
      if (entry.value["agent"] && entry.value["agent"].IsScalar()) agent = entry.value["agent"].Scalar();
      if (entry.value["task"] && entry.value["task"].IsScalar()) task = entry.value["task"].Scalar();
      origin = entry.origin;
    }
  }
  if (agent.empty() || task.empty()) return {};
  return {ConfigEntry{"env_id", YAML::Node("Safety" + agent + task + "-v0"),
                      origin + " (env_id from env: agent and task)"}};
}

// `learner: corrected` (common/learner_preset.h): every corrected switch that
// applies to the algorithm, unless the run file or --set names it.
void apply_learner_preset(RunConfig& config, const std::vector<ConfigEntry>& run_entries,
                          const std::vector<ConfigEntry>& set_entries, ConfigOrigins& origins) {
  if (config.learner != Learner::corrected) return;
  const std::string preset_origin = "learner: corrected (" + origins["learner"] + ")";
  for (const auto& [name, value] : corrected_learner_settings()) {
    const ConfigKey& key = *find_config_key(name);
    const std::string key_name(name);
    if (!key.applies_to(config.alg) || find_last_entry(run_entries, key_name) != nullptr ||
        find_last_entry(set_entries, key_name) != nullptr) {
      continue;
    }
    set_config_value(config, key, YAML::Node(std::string(value)), preset_origin);
    origins[key_name] = preset_origin;
  }
}

}  // namespace

std::filesystem::path algorithm_config_path(const std::filesystem::path& configs_dir,
                                            Algorithm alg) {
  return configs_dir / "algorithms" / (std::string(to_string(alg)) + ".yaml");
}

std::filesystem::path environment_config_path(const std::filesystem::path& configs_dir,
                                              const std::string& env_id) {
  return configs_dir / "envs" / (env_id + ".yaml");
}

std::vector<std::string> list_config_env_ids(const std::filesystem::path& configs_dir) {
  std::vector<std::string> ids;
  std::error_code error;
  const std::filesystem::path envs = configs_dir / "envs";
  if (!std::filesystem::is_directory(envs, error)) return ids;
  for (const auto& file : std::filesystem::directory_iterator(envs, error)) {
    if (file.is_regular_file() && file.path().extension() == ".yaml") {
      ids.push_back(file.path().stem().string());
    }
  }
  std::sort(ids.begin(), ids.end());
  return ids;
}

ResolvedRunConfig resolve_run_config(const RunConfigRequest& request) {
  const std::vector<ConfigEntry> run_entries =
      request.run_file.empty() ? request.run_entries : read_config_file(request.run_file);
  std::vector<ConfigEntry> later_entries = parse_set_arguments(request.set_arguments);
  later_entries.insert(later_entries.end(), request.set_entries.begin(), request.set_entries.end());
  const std::vector<ConfigEntry> set_entries = std::move(later_entries);

  ResolvedRunConfig resolved;
  RunConfig& config = resolved.config;

  // 1. The algorithm and the environment choose the default layers.
  const ConfigKey& alg_key = *find_config_key("alg");
  const ConfigEntry& alg_entry =
      choosing_entry(run_entries, set_entries, "alg", request, alg_key.valid_values());
  set_config_value(config, alg_key, alg_entry.value, alg_entry.origin);
  resolved.origins["alg"] = alg_entry.origin;

  const std::vector<std::string> valid_env_ids = request.valid_env_ids.empty()
                                                     ? list_config_env_ids(request.configs_dir)
                                                     : request.valid_env_ids;
  const ConfigKey& env_key = *find_config_key("env_id");
  const std::vector<ConfigEntry> implied = implied_env_id(run_entries, set_entries);
  const ConfigEntry& env_entry =
      implied.empty() ? choosing_entry(run_entries, set_entries, "env_id", request, comma_separated(valid_env_ids))
                      : implied.front();
  set_config_value(config, env_key, env_entry.value, env_entry.origin);
  check_env_id(config.env_id, env_entry.origin, valid_env_ids);
  resolved.origins["env_id"] = env_entry.origin;

  // 2. The layers, lowest first.
  const std::filesystem::path alg_file = algorithm_config_path(request.configs_dir, config.alg);
  const std::vector<ConfigEntry> alg_entries = read_config_file(alg_file);
  reject_run_keys(alg_entries, "an algorithm");

  const std::filesystem::path env_file =
      environment_config_path(request.configs_dir, config.env_id);
  std::error_code error;
  const bool has_env_file = std::filesystem::exists(env_file, error);
  const std::vector<ConfigEntry> env_entries =
      has_env_file ? read_config_file(env_file) : std::vector<ConfigEntry>{};
  reject_run_keys(env_entries, "an environment");

  apply_config_entries(config, alg_entries, resolved.origins);
  const RunConfig algorithm_defaults = config;
  for (const auto* layer : {&env_entries, &run_entries, &set_entries}) {
    apply_config_entries(config, *layer, resolved.origins);
  }

  apply_learner_preset(config, run_entries, set_entries, resolved.origins);

  // 3. Every key of the algorithm has a value from some layer.
  for (const ConfigKey& key : run_config_schema()) {
    if (!key.applies_to(config.alg) || resolved.origins.count(std::string(key.key)) != 0) {
      continue;
    }
    const std::string name(key.key);
    switch (key.default_source) {
      case ConfigLayer::run:
        resolved.origins[name] = "default";
        break;
      case ConfigLayer::algorithm:
        throw ConfigError("key '" + name + "' is not set: " + alg_file.string() +
                          " must list every key of alg '" + std::string(to_string(config.alg)) +
                          "' (or set it in the run file or with --set)");
      case ConfigLayer::environment:
        throw ConfigError("key '" + name + "' is not set for env_id '" + config.env_id + "': " +
                          (has_env_file ? env_file.string() + " does not list it"
                                        : "there is no " + env_file.string()) +
                          "; set it there, in the run file or with --set");
    }
  }

  reject_ineffective_multiplier_keys(config, algorithm_defaults, resolved.origins);
  check_run_config_relations(config, resolved.origins);
  return resolved;
}

}  // namespace bsg
