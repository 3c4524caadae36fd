#include "experiments/grid_file.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <fstream>
#include <set>
#include <sstream>
#include <system_error>

#include "common/config_error.h"
#include "common/config_scalar.h"
#include "common/run_config_schema.h"

namespace bsg::experiments {

namespace {

constexpr std::string_view kTopLevelKeys = "description, envs, seeds, fixed, algorithms";
constexpr std::string_view kAlgorithmKeys = "fixed, axes";

std::string location(const std::string& source_name, const YAML::Node& node) {
  const YAML::Mark mark = node.Mark();
  if (mark.is_null() || mark.line < 0) return source_name;
  // yaml-cpp counts from 0; editors count from 1.
  return source_name + ":" + std::to_string(mark.line + 1) + ":" + std::to_string(mark.column + 1);
}

// The value of `key` in a mapping, or a null node if it is absent (yaml-cpp
// otherwise hands back an undefined node that throws when inspected).
YAML::Node child(const YAML::Node& mapping, const char* key) {
  const YAML::Node value = mapping[key];
  return value.IsDefined() ? value : YAML::Node(YAML::NodeType::Null);
}

[[noreturn]] void fail(const std::string& where, const std::string& message) {
  throw ConfigError(where + ": " + message);
}

// The keys of a mapping node, checked against `allowed` (comma-separated).
void check_mapping_keys(const YAML::Node& mapping, const std::string& source_name,
                        std::string_view allowed, const std::string& what) {
  std::set<std::string> seen;
  for (const auto& pair : mapping) {
    const std::string where = location(source_name, pair.first);
    if (!pair.first.IsScalar()) fail(where, "a key of " + what + " must be a plain word");
    const std::string key = pair.first.Scalar();
    bool known = false;
    std::string_view rest = allowed;
    while (!rest.empty()) {
      const std::size_t comma = rest.find(", ");
      const std::string_view word = rest.substr(0, comma);
      if (word == key) known = true;
      rest = comma == std::string_view::npos ? std::string_view{} : rest.substr(comma + 2);
    }
    if (!known) {
      fail(where, "unknown key '" + key + "' in " + what + "; valid keys: " + std::string(allowed));
    }
    if (!seen.insert(key).second) fail(where, "key '" + key + "' appears twice in " + what);
  }
}

// A run-configuration key that a grid may set (not the ones the sweep sets).
const ConfigKey& grid_config_key(const YAML::Node& key_node, const std::string& source_name) {
  const std::string where = location(source_name, key_node);
  if (!key_node.IsScalar()) fail(where, "a configuration key must be a plain word");
  const std::string key = key_node.Scalar();
  const ConfigKey* config_key = find_config_key(key);
  if (config_key == nullptr) {
    fail(where, "unknown configuration key '" + key + "'" + unknown_key_hint(key) + "; valid keys: " + config_key_list());
  }
  if (key == "env_id" || key == "alg" || key == "seed" || key == "log_dir") {
    fail(where, "key '" + key + "' cannot be set in a grid's fixed settings or axes: use the grid's "
                "envs, algorithms and seeds (the sweep chooses each run's directory)");
  }
  return *config_key;
}

// Checks one value against the key's type and range; returns it as a setting
// and its canonical text (for duplicate detection) through `canonical`.
GridSetting make_setting(const ConfigKey& key, const YAML::Node& value,
                         const std::string& source_name, std::string& canonical) {
  GridSetting setting;
  setting.key = std::string(key.key);
  setting.origin = location(source_name, value);
  RunConfig scratch;
  set_config_value(scratch, key, value, setting.origin + " (" + setting.key + ")");
  canonical = config_value_to_yaml(scratch, key);
  if (value.IsSequence()) {
    setting.value_text = canonical;
    for (std::size_t i = 0; i < value.size(); ++i) {
      setting.name_text += (i ? "x" : "") + value[i].Scalar();
    }
  } else if (value.IsMap()) {  // env: {bombs: 12} names the run "bombs12"
    setting.value_text = canonical;
    for (const auto& pair : value) {
      setting.name_text += (setting.name_text.empty() ? "" : "_") + pair.first.Scalar() + pair.second.Scalar();
    }
  } else {
    setting.value_text = value.Scalar();
    setting.name_text = value.Scalar();
  }
  return setting;
}

std::vector<GridSetting> parse_fixed(const YAML::Node& node, const std::string& source_name,
                                     const std::string& what) {
  std::vector<GridSetting> fixed;
  if (node.IsNull()) return fixed;
  if (!node.IsMap()) fail(location(source_name, node), what + " must be a mapping of key: value");
  std::set<std::string> seen;
  for (const auto& pair : node) {
    const ConfigKey& key = grid_config_key(pair.first, source_name);
    if (!seen.insert(std::string(key.key)).second) {
      fail(location(source_name, pair.first),
           "key '" + std::string(key.key) + "' appears twice in " + what);
    }
    if (pair.second.IsMap()) {
      fail(location(source_name, pair.second), what + ": '" + std::string(key.key) +
                                                   "' must have a single value, not a mapping");
    }
    if (pair.second.IsSequence() && key.type != ValueType::integer_list &&
        key.type != ValueType::constraint_list) {
      fail(location(source_name, pair.second),
           what + ": '" + std::string(key.key) +
               "' has a list of values; a swept key belongs under 'axes' of an algorithm");
    }
    std::string canonical;
    fixed.push_back(make_setting(key, pair.second, source_name, canonical));
  }
  return fixed;
}

std::vector<GridAxis> parse_axes(const YAML::Node& node, const std::string& source_name,
                                 const std::string& what) {
  std::vector<GridAxis> axes;
  if (node.IsNull()) return axes;
  if (!node.IsMap()) {
    fail(location(source_name, node), what + " must be a mapping of key: [value, value, ...]");
  }
  std::set<std::string> seen;
  for (const auto& pair : node) {
    const ConfigKey& key = grid_config_key(pair.first, source_name);
    const std::string name(key.key);
    if (!seen.insert(name).second) {
      fail(location(source_name, pair.first), "axis '" + name + "' appears twice in " + what);
    }
    const YAML::Node& values = pair.second;
    if (!values.IsSequence() || values.size() == 0) {
      fail(location(source_name, values),
           "axis '" + name + "' in " + what + " must be a non-empty list of values, e.g. [0.001, 0.01]");
    }
    GridAxis axis{name, {}};
    std::set<std::string> canonical_values;
    for (const YAML::Node& value : values) {
      std::string canonical;
      axis.values.push_back(make_setting(key, value, source_name, canonical));
      if (!canonical_values.insert(canonical).second) {
        fail(location(source_name, value),
             "axis '" + name + "' lists the value " + canonical + " twice");
      }
    }
    axes.push_back(std::move(axis));
  }
  return axes;
}

AlgorithmGrid parse_algorithm(const YAML::Node& name_node, const YAML::Node& body,
                              const std::string& source_name) {
  const std::string where = location(source_name, name_node);
  if (!name_node.IsScalar()) fail(where, "an algorithm name must be a plain word");
  const std::string name = name_node.Scalar();
  const auto found = std::find(kAlgorithmNames.begin(), kAlgorithmNames.end(), name);
  if (found == kAlgorithmNames.end()) {
    fail(where, "unknown algorithm '" + name + "' under 'algorithms'; valid: " +
                    find_config_key("alg")->valid_values());
  }
  AlgorithmGrid grid;
  grid.alg = static_cast<Algorithm>(found - kAlgorithmNames.begin());
  if (body.IsNull()) return grid;  // `trpo:` alone: the algorithm's defaults
  if (!body.IsMap()) fail(location(source_name, body), "algorithm '" + name + "' must be a mapping "
                                                       "with 'fixed' and/or 'axes'");
  const std::string what = "algorithm '" + name + "'";
  check_mapping_keys(body, source_name, kAlgorithmKeys, what);
  grid.fixed = parse_fixed(child(body, "fixed"), source_name, what + " fixed");
  grid.axes = parse_axes(child(body, "axes"), source_name, what + " axes");
  for (const GridSetting& setting : grid.fixed) {
    for (const GridAxis& axis : grid.axes) {
      if (axis.key == setting.key) {
        fail(setting.origin, "key '" + setting.key + "' of " + what + " is both fixed and an axis");
      }
    }
  }
  auto check_applies = [&](const std::string& key, const std::string& origin) {
    const ConfigKey& config_key = *find_config_key(key);
    if (!config_key.applies_to(grid.alg)) {
      fail(origin, "key '" + key + "' does not apply to algorithm '" + name + "' (it applies to " +
                       config_key.used_by_text() + ")");
    }
  };
  for (const GridSetting& setting : grid.fixed) check_applies(setting.key, setting.origin);
  for (const GridAxis& axis : grid.axes) check_applies(axis.key, axis.values.front().origin);
  return grid;
}

std::vector<std::string> parse_env_ids(const YAML::Node& node, const std::string& source_name) {
  if (!node.IsSequence() || node.size() == 0) {
    fail(location(source_name, node), "'envs' must be a non-empty list of environment ids");
  }
  std::vector<std::string> ids;
  for (const YAML::Node& id : node) {
    if (!id.IsScalar() || id.Scalar().empty()) {
      fail(location(source_name, id), "'envs' must list environment ids such as SafetyBallCircle-v0");
    }
    if (std::find(ids.begin(), ids.end(), id.Scalar()) != ids.end()) {
      fail(location(source_name, id), "'envs' lists '" + id.Scalar() + "' twice");
    }
    ids.push_back(id.Scalar());
  }
  return ids;
}

std::vector<std::int64_t> parse_seeds(const YAML::Node& node, const std::string& source_name) {
  if (!node.IsSequence() || node.size() == 0) {
    fail(location(source_name, node), "'seeds' must be a non-empty list of integers, e.g. [0, 1, 2, 3]");
  }
  const ConfigKey& seed_key = *find_config_key("seed");
  std::vector<std::int64_t> seeds;
  for (const YAML::Node& value : node) {
    const std::string where = location(source_name, value);
    RunConfig scratch;
    set_config_value(scratch, seed_key, value, where + " (seeds)");
    if (std::find(seeds.begin(), seeds.end(), scratch.seed) != seeds.end()) {
      fail(where, "'seeds' lists " + std::to_string(scratch.seed) + " twice");
    }
    seeds.push_back(scratch.seed);
  }
  return seeds;
}

}  // namespace

GridSpec parse_grid(std::string_view yaml_text, const std::string& source_name) {
  YAML::Node document;
  try {
    document = YAML::Load(std::string(yaml_text));
  } catch (const YAML::Exception& e) {
    throw ConfigError(source_name + ": malformed YAML: " + e.what());
  }
  if (!document.IsMap()) {
    throw ConfigError(source_name + ": a grid file must be a mapping with the keys " +
                      std::string(kTopLevelKeys));
  }
  check_mapping_keys(document, source_name, kTopLevelKeys, "a grid file");
  for (const char* required : {"envs", "seeds", "algorithms"}) {
    if (!document[required].IsDefined()) {
      throw ConfigError(source_name + ": missing key '" + required + "' (a grid file needs envs, "
                                                                     "seeds and algorithms)");
    }
  }

  GridSpec grid;
  grid.source_name = source_name;
  if (const YAML::Node description = child(document, "description"); !description.IsNull()) {
    if (!description.IsScalar()) fail(location(source_name, description), "'description' must be text");
    grid.description = description.Scalar();
  }
  grid.env_ids = parse_env_ids(document["envs"], source_name);
  grid.seeds = parse_seeds(document["seeds"], source_name);
  grid.fixed = parse_fixed(child(document, "fixed"), source_name, "fixed");

  const YAML::Node algorithms = document["algorithms"];
  if (!algorithms.IsMap() || algorithms.size() == 0) {
    fail(location(source_name, algorithms),
         "'algorithms' must map at least one algorithm name to its axes, e.g. trpo: {axes: "
         "{target_kl: [0.001, 0.01]}}");
  }
  for (const auto& pair : algorithms) {
    AlgorithmGrid algorithm = parse_algorithm(pair.first, pair.second, source_name);
    for (const AlgorithmGrid& other : grid.algorithms) {
      if (other.alg == algorithm.alg) {
        fail(location(source_name, pair.first),
             "algorithm '" + std::string(to_string(algorithm.alg)) + "' appears twice");
      }
    }
    grid.algorithms.push_back(std::move(algorithm));
  }

  // A top-level fixed key must mean something to at least one algorithm.
  for (const GridSetting& setting : grid.fixed) {
    const ConfigKey& key = *find_config_key(setting.key);
    const bool used = std::any_of(grid.algorithms.begin(), grid.algorithms.end(),
                                  [&](const AlgorithmGrid& a) { return key.applies_to(a.alg); });
    if (!used) {
      fail(setting.origin, "fixed key '" + setting.key + "' applies to none of the grid's algorithms "
                           "(it applies to " + key.used_by_text() + ")");
    }
  }
  return grid;
}

GridSpec load_grid_file(const std::filesystem::path& path) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) {
    throw ConfigError("grid file not found: " + path.string());
  }
  std::ifstream in(path);
  if (!in) throw ConfigError("cannot read grid file: " + path.string());
  std::ostringstream text;
  text << in.rdbuf();
  return parse_grid(text.str(), path.string());
}

}  // namespace bsg::experiments
