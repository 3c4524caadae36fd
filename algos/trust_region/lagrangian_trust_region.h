// What TRPO-L, PDO and RCPO share over the trust-region base: one Lagrange multiplier per
// constraint (algos/lagrange/constraint_multipliers.h), stepped on this epoch's J_Cj before
// the policy step, logged after every other column and kept in the checkpoint
// (docs/algorithms.md#lagrange-multipliers). A variant calls update_multipliers() in its
// plan_step() and turns the lambdas into its surrogate or direction, or takes lagrangian_plan()
// (TRPO-L; RCPO without the line search).
#pragma once

#include <span>
#include <string>
#include <utility>
#include <vector>

#include "algos/lagrange/constraint_multipliers.h"
#include "algos/lagrange/lagrangian_weights.h"
#include "algos/trust_region/trust_region_algorithm.h"
#include "common/run_config.h"

namespace bsg::algos {

class LagrangianTrustRegion : public TrustRegionAlgorithm {
 public:
  // The multipliers' entries (names as LagrangeMultipliers::state()).
  std::vector<NamedScalar> state() const final { return multipliers_.state(); }
  void restore_state(std::span<const NamedScalar> saved) final { multipliers_.restore_state(saved); }

  double lagrange_multiplier() const { return multipliers_.value(0); }
  const LagrangeMultipliers& multipliers() const { return multipliers_; }

 protected:
  explicit LagrangianTrustRegion(const RunConfig& config) : TrustRegionAlgorithm(config), multipliers_(config) {}

  // Every lambda_j's step on its J_Cj; returns lambda_1..lambda_m.
  std::vector<double> update_multipliers(const PolicyUpdateInputs& inputs) {
    return multipliers_.update(inputs, config(), name());
  }
  // update_multipliers(), then the plan of a step on the Lagrangian
  // -l_L = (L_R - sum_j lambda_j L_Cj) / (1 + sum_j lambda_j), with the line search (TRPO-L's).
  TrustRegionPlan lagrangian_plan(const PolicyUpdateInputs& inputs) {
    ConstraintSurrogateWeights weights = lagrangian_surrogate_weights(update_multipliers(inputs));
    TrustRegionPlan plan;
    plan.surrogate.reward_weight = weights.reward;
    plan.surrogate.cost_weights = std::move(weights.costs);
    return plan;
  }
  // The multipliers' columns, last.
  std::vector<std::string> own_diagnostic_names() const override { return multipliers_.diagnostic_names(); }
  void append_own_diagnostics(PolicyUpdateResult& result) const override { multipliers_.append_to(result); }

 private:
  LagrangeMultipliers multipliers_;
};

}  // namespace bsg::algos
