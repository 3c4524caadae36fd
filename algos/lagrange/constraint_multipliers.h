// One Lagrange multiplier per constraint (docs/algorithms.md#several-constraints) for TRPO-L and
// PDO: lambda_i >= 0 with its own optimiser state (SGD, Adam moments, or the
// PID rule's integral, EMAs and history), each updated once per epoch on its
// own violation J_Ci - d_i exactly as the single multiplier (multiplier.h).
// With one constraint it is that multiplier, names and all, so a run without
// `constraints:` logs and checkpoints what it did before.
//
// Names with m >= 2: the progress columns constraint_<i>_lambda (and
// constraint_<i>_pid_p, _pid_i, _pid_d with PID), the checkpoint entries
// constraint_<i>/<the single multiplier's entry>, i = 1..m.
#pragma once

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "algos/core/algorithm.h"
#include "algos/lagrange/multiplier.h"
#include "common/run_config.h"

namespace bsg::algos {

class LagrangeMultipliers {
 public:
  // m = the config's number of constraints, each starting at lagrangian_multiplier_init.
  explicit LagrangeMultipliers(const RunConfig& config);

  int count() const { return static_cast<int>(multipliers_.size()); }
  double value(int i) const { return multipliers_.at(static_cast<std::size_t>(i)).value(); }

  // One step of every multiplier on its constraint; returns lambda_1..lambda_m.
  // Throws std::invalid_argument if the number of constraints differs from count().
  std::vector<double> update(std::span<const ConstraintEstimate> constraints);
  // The epoch's step of a Lagrangian update, before its policy step: checks J_C (naming the
  // algorithm), reads the constraints of the inputs (constraint_estimates) and steps on them.
  std::vector<double> update(const PolicyUpdateInputs& inputs, const RunConfig& config, std::string_view algorithm);

  std::vector<std::string> diagnostic_names() const;
  // Appends diagnostic_names() to an algorithm's column names (the multipliers' columns come last).
  void append_diagnostic_names(std::vector<std::string>& names) const;
  std::vector<NamedScalar> diagnostics() const;
  // Appends diagnostics() to an update's result and, with one constraint,
  // sets its lagrange_multiplier (what the progress line shows).
  void append_to(PolicyUpdateResult& result) const;
  std::vector<NamedScalar> state() const;
  // Throws std::invalid_argument if the names differ from state()'s (nothing changes then).
  void restore_state(std::span<const NamedScalar> saved);

 private:
  std::vector<LagrangeMultiplier> multipliers_;
};

}  // namespace bsg::algos
