// The per-step costs of a run's constraints (docs/algorithms.md#several-constraints): constraint
// i's cost at step t is the sum of the environment's cost terms it names, or
// the environment's own cost (the clipped sum of every term) for `all` and
// for the single constraint of a run without `constraints:`.
#pragma once

#include <Eigen/Core>
#include <span>
#include <string>
#include <vector>

#include "common/run_config.h"
#include "envs/env.h"

namespace bsg::algos {

// m = the number of constraints of a config: its `constraints:` list, else 1.
int constraint_count(const RunConfig& config);

// The limit d_i of constraint i (cost_limit for the single default one).
double constraint_limit(const RunConfig& config, int i);

// The constraints as configured, or the single default one {all, cost_limit}.
std::vector<ConstraintConfig> effective_constraints(const RunConfig& config);

class StepCostSelector {
 public:
  // The single constraint on the environment's whole cost.
  StepCostSelector();
  explicit StepCostSelector(const RunConfig& config);

  int count() const { return static_cast<int>(constraints_.size()); }

  // Binds the term names to positions in the environment's term names (the
  // order of StepResult::cost_terms, which is fixed). Throws ConfigError
  // naming the constraint and listing the environment's terms if a name is missing.
  void bind(const std::vector<std::string>& term_names, const std::string& env_id);

  // costs[i] = constraint i's cost of this step. Needs bind() first unless
  // every constraint takes the whole cost. No allocation.
  void select(const envs::StepResult& step, Eigen::Ref<Eigen::VectorXd> costs) const;

  // True if some constraint names terms (bind() is then needed).
  bool needs_terms() const;

 private:
  std::vector<ConstraintConfig> constraints_;
  std::vector<std::vector<std::size_t>> positions_;  // per constraint, indices into cost_terms
  std::size_t term_count_ = 0;
  bool bound_ = false;
};

}  // namespace bsg::algos
