#include "common/config_entries.h"

#include <fstream>
#include <map>
#include <sstream>
#include <system_error>

#include "common/config_error.h"
#include "common/message_text.h"
#include "common/run_config_schema.h"

namespace bsg {

namespace {

std::string location(const std::string& source_name, const YAML::Mark& mark) {
  if (mark.is_null()) return source_name;
  // yaml-cpp counts lines and columns from 0; editors count from 1.
  return source_name + ":" + std::to_string(mark.line + 1) + ":" + std::to_string(mark.column + 1);
}

[[noreturn]] void throw_unknown_key(const std::string& key, const std::string& where) {
  throw ConfigError(where + ": unknown key '" + printable_excerpt(key) + "'" + unknown_key_hint(key) +
                    "; valid keys: " + config_key_list());
}

}  // namespace

YAML::Node load_yaml_file(const std::filesystem::path& path) {
  std::error_code error;
  if (!std::filesystem::exists(path, error)) {
    throw ConfigError("config file not found: " + path.string());
  }
  if (std::filesystem::is_directory(path, error)) {
    throw ConfigError("config path is a directory, not a YAML file: " + path.string());
  }
  std::ifstream in(path);
  if (!in) throw ConfigError("cannot read config file: " + path.string());
  std::ostringstream text;
  text << in.rdbuf();
  try {
    return YAML::Load(text.str());
  } catch (const YAML::Exception& e) {
    throw ConfigError(path.string() + ": malformed YAML: " + e.what());
  }
}

std::vector<ConfigEntry> read_config_entries(const YAML::Node& document,
                                             const std::string& source_name) {
  std::vector<ConfigEntry> entries;
  if (!document.IsDefined() || document.IsNull()) return entries;
  if (!document.IsMap()) {
    throw ConfigError(location(source_name, document.Mark()) +
                      ": expected a mapping of 'key: value' lines at the top level");
  }
  std::map<std::string, std::string> first_seen;  // key -> where
  for (const auto& pair : document) {
    const std::string where = location(source_name, pair.first.Mark());
    if (!pair.first.IsScalar()) {
      throw ConfigError(where + ": a key must be a plain word; valid keys: " + config_key_list());
    }
    const std::string key = pair.first.Scalar();
    if (find_config_key(key) == nullptr) throw_unknown_key(key, where);
    const auto [it, inserted] = first_seen.emplace(key, where);
    if (!inserted) {
      throw ConfigError(where + ": key '" + printable_excerpt(key) + "' appears twice (first at " + it->second + ")");
    }
    entries.push_back({key, pair.second, where});
  }
  return entries;
}

std::vector<ConfigEntry> read_config_file(const std::filesystem::path& path) {
  return read_config_entries(load_yaml_file(path), path.string());
}

ConfigEntry parse_set_argument(std::string_view argument) {
  const std::string origin = "--set " + printable_excerpt(argument);
  const std::size_t equals = argument.find('=');
  if (equals == std::string_view::npos) {
    throw ConfigError(origin + ": expected key=value (e.g. --set target_kl=0.001)");
  }
  std::string key(argument.substr(0, equals));
  // Allow spaces around the key ("gamma = 0.9" passed as one argument).
  key.erase(0, key.find_first_not_of(" \t"));
  key.erase(key.find_last_not_of(" \t") + 1);
  if (key.empty()) throw ConfigError(origin + ": the key before '=' is empty");
  const bool env_parameter = key.starts_with("env.") && key.size() > 4;
  if (!env_parameter && find_config_key(key) == nullptr) throw_unknown_key(key, origin);
  const std::string value_text(argument.substr(equals + 1));
  YAML::Node value;
  try {
    value = YAML::Load(value_text);
  } catch (const YAML::Exception& e) {
    throw ConfigError(origin + ": the value is not valid YAML: " + e.what());
  }
  return make_config_entry(std::move(key), std::move(value), origin);
}

ConfigEntry make_config_entry(std::string key, YAML::Node value, std::string origin) {
  // env.<parameter>=value sets one environment parameter: env: {<parameter>: value}.
  if (key.starts_with("env.") && key.size() > 4) {
    YAML::Node mapping(YAML::NodeType::Map);
    mapping[key.substr(4)] = value;
    return make_config_entry("env", mapping, std::move(origin));
  }
  if (find_config_key(key) == nullptr) throw_unknown_key(key, origin);
  return {std::move(key), std::move(value), std::move(origin)};
}

std::vector<ConfigEntry> parse_set_arguments(const std::vector<std::string>& arguments) {
  std::vector<ConfigEntry> entries;
  entries.reserve(arguments.size());
  for (const std::string& argument : arguments) entries.push_back(parse_set_argument(argument));
  return entries;
}

}  // namespace bsg
