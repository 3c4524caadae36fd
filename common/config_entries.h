// Reading configuration layers: a YAML file or a list of `--set key=value`
// arguments becomes a list of (key, value, origin) entries. Unknown keys,
// duplicate keys, malformed YAML and missing files are reported here, each
// naming the file and line (or the --set argument) at fault.
#pragma once

#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace bsg {

struct ConfigEntry {
  std::string key;     // a key of run_config_schema()
  YAML::Node value;
  std::string origin;  // "path:line:column" or "--set key=value", for messages
};

// Parses the file; throws ConfigError naming the path if it is missing or
// unreadable, and the path with yaml-cpp's message if it is malformed.
YAML::Node load_yaml_file(const std::filesystem::path& path);

// The top-level `key: value` pairs of a parsed document (an empty document
// gives none). `source_name` (usually the path) prefixes every origin.
// Throws ConfigError on a non-mapping document, a non-scalar or duplicate
// key, or a key that is not in the schema (listing the valid keys).
std::vector<ConfigEntry> read_config_entries(const YAML::Node& document,
                                             const std::string& source_name);

// load_yaml_file + read_config_entries.
std::vector<ConfigEntry> read_config_file(const std::filesystem::path& path);

// One `--set` argument "key=value": the value is parsed as a YAML scalar (or a
// flow sequence such as [32, 32]) and later type-checked like a file value.
// "env.bombs=12" is the environment parameter bombs: the same as "env={bombs: 12}".
std::vector<ConfigEntry> parse_set_arguments(const std::vector<std::string>& arguments);
ConfigEntry parse_set_argument(std::string_view argument);

// The entry of `key` with a value already parsed (bsg.train's keywords and dict), named `origin`
// in messages: "env.bombs" is the environment parameter bombs as in parse_set_argument. Throws
// ConfigError on a key that is not in the schema (with the other libraries' spelling pointed to).
ConfigEntry make_config_entry(std::string key, YAML::Node value, std::string origin);

}  // namespace bsg
