// CRPO, Constraint-Rectified Policy Optimisation (docs/algorithms.md#crpo; Xu, Liang and Lan
// 2021, "CRPO: A New Approach for Safe Reinforcement Learning with Convergence Guarantee",
// Algorithm 1), as a variant of the trust-region base (trust_region_algorithm.h). Each epoch,
// on the pooled J_Ci of this epoch's episodes:
//   - if some constraint is violated beyond the tolerance, J_Ci > d_i + eta, the TRPO step
//     minimises that constraint's cost surrogate: -l = -L_Cj (the TRPO step on the advantages
//     -A^Cj), line search A on l = L_Cj;
//   - otherwise the TRPO step on the reward, exactly as TRPO's.
// With several violated constraints the paper rectifies any one of them; this one takes the
// largest excess J_Ci - (d_i + eta), the first of equal ones (crpo_rectified_constraint).
// No multiplier, no state. Column crpo_case: 0 for a reward step, j for a step on constraint j.
//
// Parameters (RunConfig): those of TRPO, cost_limit (or constraints:), and
// crpo_tolerance eta (OmniSafe's `distance`: 2.0 there and in RunConfig; 0 in configs/algorithms/crpo.yaml).
#pragma once

#include <span>
#include <string>
#include <vector>

#include "algos/trust_region/trust_region_algorithm.h"
#include "common/run_config.h"

namespace bsg::algos {

// 0 if every J_Ci <= d_i + tolerance, else the 1-based index of the constraint with the
// largest J_Ci - (d_i + tolerance) (the lowest index among equal ones).
int crpo_rectified_constraint(std::span<const ConstraintEstimate> constraints, double tolerance);

class Crpo final : public TrustRegionAlgorithm {
 public:
  // Throws std::invalid_argument if crpo_tolerance is negative or not finite.
  explicit Crpo(const RunConfig& config);

  std::string_view name() const override { return "crpo"; }

 private:
  TrustRegionPlan plan_step(const PolicyUpdateInputs& inputs) override;
  std::vector<std::string> own_diagnostic_names() const override { return {"crpo_case"}; }
};

}  // namespace bsg::algos
