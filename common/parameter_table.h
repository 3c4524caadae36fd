// One mechanism for bsg's two tables of named settings: the run
// configuration's keys (common/run_config_schema.cpp, rows over RunConfig)
// and the environment description's parameters
// (envs/description/env_parameters.cpp, rows over EnvDescription). A row of
// either table names a member of its struct, the member's value type and its
// valid range or choices; what a row's value may be, how text becomes a value
// and how a value is written back are decided here, once, so both tables parse,
// check and print values alike. What differs stays with each table: who has a
// key (tasks and agent, or layer and algorithms) and how its errors read.
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "common/closest_name.h"
#include "common/config_scalar.h"

namespace bsg {

enum class ValueType { boolean, integer, real, text, choice, integer_list, constraint_list, mapping };
std::string_view to_string(ValueType type);

// Bounds of an integer, a real, or each element of an integer list.
struct NumericRange {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_inclusive = false;
  bool max_inclusive = false;

  static constexpr NumericRange any() { return {}; }
  static constexpr NumericRange closed(double min, double max) { return {min, max, true, true}; }
  static constexpr NumericRange open_closed(double min, double max) { return {min, max, false, true}; }
  static constexpr NumericRange open(double min, double max) { return {min, max, false, false}; }
  static constexpr NumericRange closed_open(double min, double max) { return {min, max, true, false}; }
  static constexpr NumericRange at_least(double min) {
    return {min, std::numeric_limits<double>::infinity(), true, false};
  }
  static constexpr NumericRange above(double min) {
    return {min, std::numeric_limits<double>::infinity(), false, false};
  }

  bool contains(double value) const;
  std::string to_string() const;         // interval: "(0, 1]", "[1, inf)"
  std::string inequality_text() const;   // "> 0", ">= 1", "any finite number"; else the interval
};

// Why text could not become a value of a row.
enum class ScalarProblem { none, not_a_value, out_of_range };

// Reads `text` as a value of type T (bool, int, std::int64_t, double or
// std::string) into `out`, checking numbers against `range`; `out` is left
// unchanged unless the result is ScalarProblem::none. Text is taken as it is
// (a string value only has to be non-empty).
ScalarProblem parse_scalar(std::string_view text, const NumericRange& range, bool& out);
ScalarProblem parse_scalar(std::string_view text, const NumericRange& range, int& out);
ScalarProblem parse_scalar(std::string_view text, const NumericRange& range, std::int64_t& out);
ScalarProblem parse_scalar(std::string_view text, const NumericRange& range, double& out);
ScalarProblem parse_scalar(std::string_view text, const NumericRange& range, std::string& out);

// The value as text that parse_scalar reads back to the same value (reals in
// shortest round-trip form, booleans as true/false).
std::string scalar_text(bool value);
std::string scalar_text(int value);
std::string scalar_text(std::int64_t value);
std::string scalar_text(double value);
std::string scalar_text(const std::string& value);

// The row of `rows` whose key (row.info.key) is `key`, or nullptr.
template <typename Row>
const Row* find_row(const std::vector<Row>& rows, std::string_view key) {
  for (const Row& row : rows) {
    if (row.info.key == key) return &row;
  }
  return nullptr;
}

// The key of `rows` closest in spelling to `unknown` if it is a likely typo, else "".
template <typename Row>
std::string closest_row_key(const std::vector<Row>& rows, std::string_view unknown) {
  std::vector<std::string_view> keys;
  keys.reserve(rows.size());
  for (const Row& row : rows) keys.push_back(row.info.key);
  return closest_name(unknown, keys);
}

}  // namespace bsg
