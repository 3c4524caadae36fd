// What PPO, PPO-Lag, FOCOPS, CUP, P3O and IPO share around their losses
// (docs/algorithms.md#first-order-updates): the policy's Adam, the Lagrange
// multipliers of the constrained ones (one per constraint, updated before
// the policy, constraint_multipliers.h), their columns and their saved state.
//
// Columns: the common five, Misc/StopIter and Misc/gradient_norm
// (first_order_update.h), the algorithm's own, then the multipliers'.
// State: the multipliers' entries, then PolicyAdam's.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "algos/core/algorithm.h"
#include "algos/first_order/first_order_update.h"
#include "algos/lagrange/constraint_multipliers.h"
#include "common/run_config.h"

namespace bsg::algos {

class FirstOrderAlgorithm : public OnPolicyAlgorithm {
 public:
  std::vector<std::string> diagnostic_names() const override;
  std::vector<NamedScalar> state() const override;
  // Throws std::invalid_argument if the entries are not state()'s kind.
  void restore_state(std::span<const NamedScalar> saved) override;

  // The multipliers of a constrained algorithm; nullptr for PPO.
  const LagrangeMultipliers* multipliers() const { return constrained_ ? &multipliers_ : nullptr; }

 protected:
  // own_columns: the algorithm's columns between the first-order ones and the multipliers'.
  FirstOrderAlgorithm(const RunConfig& config, bool constrained, std::vector<std::string> own_columns);

  // Every multiplier's step on its J_Cj (constrained algorithms only); returns lambda_1..lambda_m.
  std::vector<double> update_multipliers(const PolicyUpdateInputs& inputs);
  PolicyAdam& adam() { return adam_; }

  // The passes of an update that starts at theta_old: begin_policy_update (theta_old and the
  // surrogates before), then minibatch_passes of `sample_loss` with KL_i to theta_old.
  struct PassesFromStart {
    PolicyUpdateStart start;
    MinibatchPassesResult passes;
  };
  PassesFromStart passes_from_start(const PolicyUpdateInputs& inputs, const SampleLossFunction& sample_loss,
                                    const MinibatchStepHook& before_step = {});

  // The update's columns: `common` (common_diagnostics), the passes', `own` (in
  // own_columns order), then the multipliers'.
  PolicyUpdateResult make_result(std::vector<NamedScalar> common, const MinibatchPassesResult& passes,
                                 std::vector<NamedScalar> own) const;

 private:
  bool constrained_;
  std::vector<std::string> own_columns_;
  LagrangeMultipliers multipliers_;
  PolicyAdam adam_;
};

}  // namespace bsg::algos
