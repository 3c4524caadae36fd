// The SGD multiplier rule (TRPO-L's, the original's): lambda <- max(0, lambda + alpha_lambda (J_C - d)),
// a gradient step on -lambda (J_C - d) and the projection onto lambda >= 0. No state.
#pragma once

#include <memory>

#include "algos/lagrange/multiplier_rule.h"

namespace bsg::algos {

class SgdMultiplierRule final : public MultiplierRule {
 public:
  explicit SgdMultiplierRule(double learning_rate) : learning_rate_(learning_rate) {}

  std::unique_ptr<MultiplierRule> clone() const override { return std::make_unique<SgdMultiplierRule>(*this); }
  double step(double lambda, double mean_episode_cost, double cost_limit) override;

 private:
  double learning_rate_;  // alpha_lambda
};

}  // namespace bsg::algos
