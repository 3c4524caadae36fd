// The keys of an EnvDescription (env_description.h) in one table: type, unit,
// the tasks (and agent) that have the key, valid values and meaning. Overrides
// from run files, the command line and Python are applied and checked here,
// and the description is printed from here, so all three read the same keys.
#pragma once

#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "common/parameter_table.h"
#include "envs/description/env_description.h"

namespace bsg::envs {

// Bit set of the tasks a key applies to.
using TaskSet = unsigned;
inline constexpr TaskSet kCircle = 1, kGather = 2, kReach = 4, kRun = 8;
inline constexpr TaskSet kAllTasks = kCircle | kGather | kReach | kRun;

// A key's row as the rest of bsg sees it; the value type and range are the
// shared ones of common/parameter_table.h, as the run configuration's keys.
struct EnvParameter {
  std::string_view key;
  ValueType type = ValueType::real;  // boolean, integer, real, text or choice
  TaskSet tasks = kAllTasks;
  std::string_view agent;        // non-empty: only this agent has the key
  std::string_view unit;         // "m", "s", "m/s", "" (a count or a factor)
  NumericRange range;            // integer and real keys
  std::vector<std::string_view> choices;  // choice keys: the valid values
  std::string_view description;

  // What a value may be: e.g. "> 0", ">= 1", "Ball, Car, Drone, Ant".
  std::string valid_text() const;
};

// (key, value) pairs as text: "bombs" → "12". Applied in order.
using EnvOverrides = std::vector<std::pair<std::string, std::string>>;

// Every key, in the order to_yaml() writes them.
const std::vector<EnvParameter>& env_parameters();

// nullptr if `key` is not a parameter.
const EnvParameter* find_env_parameter(std::string_view key);

// The key's value as text that set_env_parameter reads back to the same value
// (reals in shortest round-trip form).
std::string env_parameter_text(const EnvDescription& description, const EnvParameter& parameter);

// True if the description's task (and agent) have the key.
bool applies_to(const EnvParameter& parameter, const EnvDescription& description);

// Applies `overrides` to `base` and checks the result. `agent` or `task`
// restart from the standard description of the new combination (the other
// keys then apply on top); `zone_type` resets `zone_radius` to the type's own
// radius unless zone_radius is given too. Throws std::invalid_argument with
// one line naming the key and the value: an unknown key (with the closest
// key), a value of the wrong type or out of range, a key the task or agent
// does not have, an unknown agent or task, counts that cannot be placed.
EnvDescription apply_env_overrides(const EnvDescription& base, const EnvOverrides& overrides);

// Checks a whole description (every apply_env_overrides result passes).
void check_env_description(const EnvDescription& description);

// Every key the description's task and agent have, as (key, text) pairs:
// apply_env_overrides(standard, to_env_overrides(d)) == d.
EnvOverrides to_env_overrides(const EnvDescription& description);

// The description as YAML, one `key: value  # meaning [unit]` line per key
// that applies to its task and agent.
std::string to_yaml(const EnvDescription& description);

}  // namespace bsg::envs
