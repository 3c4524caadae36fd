#include "common/parameter_table.h"

#include <cmath>
#include <limits>

namespace bsg {

std::string_view to_string(ValueType type) {
  switch (type) {
    case ValueType::boolean: return "bool";
    case ValueType::integer: return "int";
    case ValueType::real: return "real";
    case ValueType::text: return "string";
    case ValueType::choice: return "choice";
    case ValueType::integer_list: return "int list";
    case ValueType::constraint_list: return "constraint list";
    case ValueType::mapping: return "mapping";
  }
  return "<invalid>";
}

bool NumericRange::contains(double value) const {
  const bool above_min = min_inclusive ? value >= min : value > min;
  const bool below_max = max_inclusive ? value <= max : value < max;
  return above_min && below_max;
}

namespace {

std::string bound_text(double x) {
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  if (x == std::floor(x) && std::fabs(x) < 1e15) return std::to_string(static_cast<long long>(x));
  return format_config_real(x);
}

}  // namespace

std::string NumericRange::to_string() const {
  std::string text;
  text += min_inclusive ? '[' : '(';
  text += bound_text(min);
  text += ", ";
  text += bound_text(max);
  text += max_inclusive ? ']' : ')';
  return text;
}

std::string NumericRange::inequality_text() const {
  if (std::isinf(max) && max > 0) {
    if (std::isinf(min) && min < 0) return "any finite number";
    return (min_inclusive ? ">= " : "> ") + bound_text(min);
  }
  return to_string();
}

ScalarProblem parse_scalar(std::string_view text, const NumericRange&, bool& out) {
  const auto value = parse_config_bool(text);
  if (!value) return ScalarProblem::not_a_value;
  out = *value;
  return ScalarProblem::none;
}

ScalarProblem parse_scalar(std::string_view text, const NumericRange& range, std::int64_t& out) {
  const auto value = parse_config_integer(text);
  if (!value) return ScalarProblem::not_a_value;
  if (!range.contains(static_cast<double>(*value))) return ScalarProblem::out_of_range;
  out = *value;
  return ScalarProblem::none;
}

ScalarProblem parse_scalar(std::string_view text, const NumericRange& range, int& out) {
  std::int64_t wide = 0;
  const ScalarProblem problem = parse_scalar(text, range, wide);
  if (problem != ScalarProblem::none) return problem;
  // The range is checked first: a number beyond it reads as out of range even
  // when it would not fit an int either.
  if (wide < std::numeric_limits<int>::min() + 1 || wide > std::numeric_limits<int>::max()) {
    return ScalarProblem::not_a_value;
  }
  out = static_cast<int>(wide);
  return ScalarProblem::none;
}

ScalarProblem parse_scalar(std::string_view text, const NumericRange& range, double& out) {
  const auto value = parse_config_real(text);
  if (!value) return ScalarProblem::not_a_value;
  if (!range.contains(*value)) return ScalarProblem::out_of_range;
  out = *value;
  return ScalarProblem::none;
}

ScalarProblem parse_scalar(std::string_view text, const NumericRange&, std::string& out) {
  if (text.empty()) return ScalarProblem::not_a_value;
  out = std::string(text);
  return ScalarProblem::none;
}

std::string scalar_text(bool value) { return value ? "true" : "false"; }
std::string scalar_text(int value) { return std::to_string(value); }
std::string scalar_text(std::int64_t value) { return std::to_string(value); }
std::string scalar_text(double value) { return format_config_real(value); }
std::string scalar_text(const std::string& value) { return value; }

}  // namespace bsg
