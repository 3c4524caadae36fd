// The `constraints:` key of a run (docs/algorithms.md#several-constraints): a list of
// constraints, each summing some of the environment's named cost terms (or
// taking `all` of its cost, the clipped sum the learner sees without the key)
// against its own limit d_i on the undiscounted episode cost:
//
//   constraints:
//     - terms: [cost_outside_bounds]
//       limit: 20
//     - terms: [cost_velocity_violation]
//       limit: 5
//
// Absent, a run has one constraint: the environment's cost against cost_limit.
// Which term names exist depends on the environment; the learner checks them
// (algos/core/constraint_costs.h), this file only the list's form.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace YAML {
class Node;
}

namespace bsg {

// The most constraints a run may have (CPO's and PCPO's exact solvers try
// every active set, 2^m of them: algos/trust_region/constraint_qp.h).
inline constexpr int kMaxConstraintCount = 8;

// The term list that stands for the environment's whole (clipped) cost.
inline constexpr std::string_view kAllCostTerms = "all";

struct ConstraintConfig {
  std::vector<std::string> terms;  // cost term names, or {"all"}
  double limit = 0.0;              // d_i >= 0, per episode
  bool operator==(const ConstraintConfig&) const = default;

  bool sums_all_terms() const { return terms.size() == 1 && terms.front() == kAllCostTerms; }
  // "cost_outside_bounds+cost_velocity_violation" or "all", for messages and reports.
  std::string terms_text() const;
};

// Reads the key's YAML value; throws ConfigError naming `origin` and the
// fault: not a list, an empty list, more than `max_constraints`, an element
// that is not a mapping of `terms` and `limit` (and nothing else), no terms,
// `all` beside other names, a term named twice, a limit that is missing,
// negative or not finite.
std::vector<ConstraintConfig> parse_constraint_list(const YAML::Node& value, const std::string& origin,
                                                    int max_constraints);

// The list as one line of flow YAML that parse_constraint_list reads back to
// the same list: [{terms: [a, b], limit: 20}, {terms: all, limit: 5}].
std::string constraint_list_to_yaml(const std::vector<ConstraintConfig>& constraints);

}  // namespace bsg
