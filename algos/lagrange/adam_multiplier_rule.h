// The Adam multiplier rule (PDO's and the first-order algorithms'): an Adam step (beta 0.9/0.999,
// eps 1e-8, PyTorch's defaults) on the gradient -(J_C - d), then lambda <- max(0, lambda). The
// moments persist across epochs and are not reset by the projection; they are checkpointed
// as lagrange_multiplier_adam_m, _v and _t.
#pragma once

#include <memory>
#include <span>
#include <vector>

#include "algos/lagrange/multiplier_rule.h"
#include "common/adam.h"

namespace bsg::algos {

class AdamMultiplierRule final : public MultiplierRule {
 public:
  // Throws std::invalid_argument if learning_rate is not positive (Adam's check).
  explicit AdamMultiplierRule(double learning_rate);

  std::unique_ptr<MultiplierRule> clone() const override { return std::make_unique<AdamMultiplierRule>(*this); }
  double step(double lambda, double mean_episode_cost, double cost_limit) override;
  std::vector<NamedScalar> state() const override;
  void restore_state(std::span<const NamedScalar> saved) override;

 private:
  Adam adam_;
};

}  // namespace bsg::algos
