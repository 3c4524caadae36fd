#include "common/run_config_yaml.h"

#include <yaml-cpp/yaml.h>

#include <fstream>
#include <sstream>

#include "common/config_entries.h"
#include "common/config_error.h"
#include "common/run_config_checks.h"
#include "common/run_config_schema.h"

namespace bsg {

namespace {

RunConfig from_document(const YAML::Node& document, const std::string& source_name,
                        const std::vector<std::string>& valid_env_ids) {
  const std::vector<ConfigEntry> entries = read_config_entries(document, source_name);
  RunConfig config;
  ConfigOrigins origins;
  for (const char* chooser : {"alg", "env_id"}) {
    const ConfigEntry* entry = find_last_entry(entries, chooser);
    if (entry == nullptr) {
      throw ConfigError(source_name + ": resolved config lacks key '" + std::string(chooser) +
                        "'");
    }
    set_config_value(config, *find_config_key(chooser), entry->value, entry->origin);
    origins[chooser] = entry->origin;
  }
  if (!valid_env_ids.empty()) check_env_id(config.env_id, origins["env_id"], valid_env_ids);
  apply_config_entries(config, entries, origins);
  // Run directories written before the `dtype` key existed were trained in
  // float64 throughout: they resume in float64.
  // No env: block: the standard description of env_id (as written since the key exists).
  if (origins.count("env") == 0) origins["env"] = source_name + " (no env: the standard description)";
  // No tensorboard: on (to_yaml names the key only when it is off).
  if (origins.count("tensorboard") == 0) origins["tensorboard"] = source_name + " (no tensorboard: on)";
  // No joint_control: off (to_yaml names the key only when it is on).
  if (origins.count("joint_control") == 0) origins["joint_control"] = source_name + " (no joint_control: off)";
  // No multiplier_schedule: epoch, the off-policy -lag schedule before the key (to_yaml names the
  // key, and the window with it, only for update_round or a window of its own).
  if (origins.count("multiplier_schedule") == 0) {
    origins["multiplier_schedule"] = source_name + " (no multiplier_schedule: epoch, as before the key)";
  }
  if (origins.count("multiplier_window") == 0 && config.off_policy.multiplier_schedule == MultiplierSchedule::epoch) {
    origins["multiplier_window"] = source_name + " (no multiplier_window: unused by the epoch schedule)";
  }
  if (origins.count("dtype") == 0) {
    config.dtype = Dtype::float64;
    origins["dtype"] = source_name + " (no dtype: written before the key existed, float64)";
  }
  for (const ConfigKey& key : run_config_schema()) {
    if (key.type == ValueType::constraint_list) continue;  // absent: one constraint (cost_limit)
    if (key.applies_to(config.alg) && origins.count(std::string(key.key)) == 0) {
      throw ConfigError(source_name + ": resolved config lacks key '" + std::string(key.key) +
                        "' (" + std::string(key.description) + ")");
    }
  }
  check_run_config_relations(config, origins);
  return config;
}

// Which keys the text names: those to_yaml leaves out stand for the value a run directory written
// before the key implied, which is what reading a resolved config assumes, but not what layering
// the text over the algorithm and environment files as a run file gives.
enum class KeysWritten { as_in_run_directories, every_key };

std::string resolved_yaml(const RunConfig& config, KeysWritten written) {
  const bool omit_implied = written == KeysWritten::as_in_run_directories;
  std::ostringstream out;
  out << "# bsg run configuration, resolved: configs/algorithms/" << to_string(config.alg)
      << ".yaml <- configs/envs/" << config.env_id << ".yaml <- run file <- --set\n";
  ConfigLayer section = ConfigLayer::run;
  bool first = true;
  for (const ConfigKey& key : run_config_schema()) {
    if (!key.applies_to(config.alg)) continue;
    if (key.type == ValueType::constraint_list && config.constraints.empty()) continue;  // as before the key
    // No env: block for a standard environment, as before the key existed.
    if (key.type == ValueType::mapping && config.env.empty()) continue;
    // tensorboard only when off: a default run's config.yaml and checkpoint as before the key.
    if (omit_implied && key.key == "tensorboard" && config.tensorboard) continue;
    // joint_control only when on: every other run's config.yaml and checkpoint as before the key.
    if (omit_implied && key.key == "joint_control" && !config.joint_control) continue;
    // The multiplier schedule only when it is not the epoch schedule of before the keys (and the
    // window then only if it is not the default): an epoch run's config.yaml and checkpoint as before.
    const bool epoch_schedule = config.off_policy.multiplier_schedule == MultiplierSchedule::epoch;
    if (omit_implied && key.key == "multiplier_schedule" && epoch_schedule) continue;
    if (omit_implied && key.key == "multiplier_window" && epoch_schedule &&
        config.off_policy.multiplier_window == OffPolicyKeys{}.multiplier_window) {
      continue;
    }
    if (first || key.default_source != section) {
      section = key.default_source;
      out << "# --- " << to_string(section) << " ---\n";
      first = false;
    }
    out << key.key << ": " << config_value_to_yaml(config, key) << "  # " << key.description
        << "\n";
  }
  return out.str();
}

}  // namespace

std::string to_yaml(const RunConfig& config) { return resolved_yaml(config, KeysWritten::as_in_run_directories); }

std::string to_run_file_yaml(const RunConfig& config) { return resolved_yaml(config, KeysWritten::every_key); }

void write_run_config(const RunConfig& config, const std::filesystem::path& path) {
  std::ofstream out(path, std::ios::trunc);
  if (!out) throw ConfigError("cannot write run config to " + path.string());
  out << to_yaml(config);
  out.flush();
  if (!out) throw ConfigError("failed writing run config to " + path.string());
}

RunConfig run_config_from_yaml(std::string_view yaml_text, const std::string& source_name,
                               const std::vector<std::string>& valid_env_ids) {
  YAML::Node document;
  try {
    document = YAML::Load(std::string(yaml_text));
  } catch (const YAML::Exception& e) {
    throw ConfigError(source_name + ": malformed YAML: " + e.what());
  }
  return from_document(document, source_name, valid_env_ids);
}

RunConfig load_resolved_run_config(const std::filesystem::path& path,
                                   const std::vector<std::string>& valid_env_ids) {
  return from_document(load_yaml_file(path), path.string(), valid_env_ids);
}

}  // namespace bsg
