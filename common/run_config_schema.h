// The schema of RunConfig: one table listing every key (its type, layer, range, algorithms and a
// one-line description), put together by run_config_schema.cpp from RunConfig's own rows and its
// groups' (common/trust_region_keys.cpp, multiplier_keys.cpp, first_order_keys.cpp,
// off_policy_keys.cpp); and the typed, range-checked assignment of a YAML value to a key.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "common/parameter_table.h"
#include "common/run_config.h"

namespace YAML {
class Node;
}

namespace bsg {

// Where a key's default comes from: the run file (or --set), the algorithm
// file configs/algorithms/<alg>.yaml, or the environment file
// configs/envs/<env_id>.yaml. Any later layer may override any key.
enum class ConfigLayer { run, algorithm, environment };
std::string_view to_string(ConfigLayer layer);

// Bit set of the algorithms a key applies to.
// 64 bits: the table has outgrown 32 algorithms.
using AlgorithmSet = std::uint64_t;
constexpr AlgorithmSet algorithm_bit(Algorithm alg) { return AlgorithmSet{1} << static_cast<unsigned>(alg); }
static_assert(kAlgorithmNames.size() < 64, "AlgorithmSet holds one bit per algorithm");
inline constexpr AlgorithmSet kAllAlgorithms = (AlgorithmSet{1} << kAlgorithmNames.size()) - 1u;

struct ConfigKey {
  std::string_view key;
  ValueType type = ValueType::boolean;
  ConfigLayer default_source = ConfigLayer::algorithm;
  NumericRange range;                          // integer, real, integer_list
  std::span<const std::string_view> choices;   // choice
  AlgorithmSet used_by = kAllAlgorithms;
  std::string_view description;

  bool applies_to(Algorithm alg) const { return (used_by & algorithm_bit(alg)) != 0; }
  std::string valid_values() const;  // range, choices, or "non-empty text"
  std::string used_by_text() const;  // "all" or e.g. "lag-trpo, pdo"
};

// Every key, in the order to_yaml() writes them.
const std::vector<ConfigKey>& run_config_schema();

// The schema as a Markdown table (key, type, default from, valid values,
// algorithms, description), as configs/README.md shows it.
std::string config_schema_markdown();

// nullptr if `key` is not a configuration key.
const ConfigKey* find_config_key(std::string_view key);

// "env_id, alg, seed, ..." in schema order, for error messages.
std::string config_key_list();

// What an error about the unknown key `unknown` suggests: " (did you mean 'polyak'? tau
// in Stable-Baselines3, CleanRL and Tianshou)" for another library's name of a key
// (common/foreign_key_spellings.h), else " (did you mean 'gamma'?)" for the key closest in
// spelling if it is a likely typo, else "".
std::string unknown_key_hint(std::string_view unknown);

// Checks `value` against the key's type and range and stores it in `config`.
// Throws ConfigError naming the key, the value and `origin` (e.g.
// "configs/runs/x.yaml:3:1" or "--set gamma=2").
void set_config_value(RunConfig& config, const ConfigKey& key, const YAML::Node& value,
                      const std::string& origin);

// The key's value in `config` as YAML text that set_config_value reads back
// to the same value (reals are written in shortest round-trip form).
std::string config_value_to_yaml(const RunConfig& config, const ConfigKey& key);

}  // namespace bsg
