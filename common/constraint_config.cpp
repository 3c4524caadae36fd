#include "common/constraint_config.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>

#include "common/config_error.h"
#include "common/config_scalar.h"

namespace bsg {
namespace {

constexpr std::string_view kForm =
    "a list of {terms: [<cost term>, ...] or all, limit: <d >= 0>}, e.g. "
    "[{terms: [cost_outside_bounds], limit: 20}, {terms: [cost_velocity_violation], limit: 5}]";

[[noreturn]] void fail(const std::string& origin, const std::string& what) {
  throw ConfigError(origin + ": key 'constraints' " + what + "; expected " + std::string(kForm));
}

std::vector<std::string> read_terms(const YAML::Node& node, const std::string& origin, const std::string& which) {
  std::vector<std::string> terms;
  if (node.IsScalar()) {
    terms.push_back(node.Scalar());
  } else if (node.IsSequence()) {
    for (const YAML::Node& element : node) {
      if (!element.IsScalar() || element.Scalar().empty()) fail(origin, which + " has a term that is not a name");
      terms.push_back(element.Scalar());
    }
  } else {
    fail(origin, which + " has no 'terms'");
  }
  if (terms.empty() || terms.front().empty()) fail(origin, which + " has an empty 'terms' list");
  for (std::size_t i = 0; i < terms.size(); ++i) {
    if (terms[i] == kAllCostTerms && terms.size() > 1) {
      fail(origin, which + " names 'all' beside other terms ('all' is the whole cost; name it alone)");
    }
    if (std::find(terms.begin(), terms.begin() + static_cast<std::ptrdiff_t>(i), terms[i]) !=
        terms.begin() + static_cast<std::ptrdiff_t>(i)) {
      fail(origin, which + " names the term '" + terms[i] + "' twice");
    }
  }
  return terms;
}

}  // namespace

std::string ConstraintConfig::terms_text() const {
  std::string text;
  for (const std::string& term : terms) text += (text.empty() ? "" : "+") + term;
  return text;
}

std::vector<ConstraintConfig> parse_constraint_list(const YAML::Node& value, const std::string& origin,
                                                    int max_constraints) {
  if (!value.IsSequence()) fail(origin, "is not a list");
  if (value.size() == 0) {
    fail(origin, "is an empty list (leave the key out for the single constraint on the environment's cost "
                 "against cost_limit)");
  }
  if (static_cast<int>(value.size()) > max_constraints) {
    fail(origin, "lists " + std::to_string(value.size()) + " constraints, at most " +
                     std::to_string(max_constraints) + " are supported");
  }
  std::vector<ConstraintConfig> constraints;
  for (std::size_t i = 0; i < value.size(); ++i) {
    const YAML::Node element = value[i];
    const std::string which = "constraint " + std::to_string(i + 1);
    if (!element.IsMap()) fail(origin, which + " is not a mapping");
    for (const auto& field : element) {
      const std::string name = field.first.IsScalar() ? field.first.Scalar() : std::string("?");
      if (name != "terms" && name != "limit") fail(origin, which + " has the unknown field '" + name + "'");
    }
    ConstraintConfig constraint;
    const YAML::Node terms = element["terms"];
    if (!terms.IsDefined()) fail(origin, which + " has no 'terms'");
    constraint.terms = read_terms(terms, origin, which);
    const YAML::Node limit = element["limit"];
    if (!limit.IsDefined() || !limit.IsScalar()) fail(origin, which + " has no 'limit'");
    const auto parsed = parse_config_real(limit.Scalar());
    if (!parsed || !std::isfinite(*parsed)) fail(origin, which + " has the limit '" + limit.Scalar() + "', not a number");
    if (*parsed < 0.0) {
      throw ConfigError(origin + ": key 'constraints': " + which + " has the negative limit " + limit.Scalar() +
                        "; a limit d_i on the episode cost must be >= 0");
    }
    constraint.limit = *parsed;
    constraints.push_back(std::move(constraint));
  }
  return constraints;
}

std::string constraint_list_to_yaml(const std::vector<ConstraintConfig>& constraints) {
  std::string text = "[";
  for (std::size_t i = 0; i < constraints.size(); ++i) {
    const ConstraintConfig& constraint = constraints[i];
    text += i ? ", {terms: " : "{terms: ";
    if (constraint.sums_all_terms()) {
      text += std::string(kAllCostTerms);
    } else {
      text += "[";
      for (std::size_t j = 0; j < constraint.terms.size(); ++j) text += (j ? ", " : "") + constraint.terms[j];
      text += "]";
    }
    text += ", limit: " + format_config_real(constraint.limit) + "}";
  }
  return text + "]";
}

}  // namespace bsg
