// How a Lagrange multiplier moves once per epoch (docs/algorithms.md#lagrange-multipliers): the
// interface of the `lambda_optimizer` rules, SGD (sgd_multiplier_rule.h), Adam
// (adam_multiplier_rule.h) and PID (pid_multiplier_rule.h). LagrangeMultiplier (multiplier.h)
// keeps lambda and applies an upper bound; the rule owns its step and its own state.
// A new rule is a class here, a value of LambdaOptimizer and a case in make_multiplier_rule.
#pragma once

#include <memory>
#include <span>
#include <vector>

#include "algos/core/algorithm.h"
#include "algos/lagrange/pid_lagrangian.h"
#include "common/run_config.h"

namespace bsg::algos {

class MultiplierRule {
 public:
  virtual ~MultiplierRule() = default;
  virtual std::unique_ptr<MultiplierRule> clone() const = 0;

  // One step from lambda on the loss -lambda (J_C - d); returns the new lambda >= 0.
  virtual double step(double lambda, double mean_episode_cost, double cost_limit) = 0;

  // The rule's progress columns after "LagrangeMultiplier" (none by default).
  virtual std::vector<NamedScalar> diagnostics() const { return {}; }
  // The rule's checkpoint entries after "lagrange_multiplier" (none by default).
  virtual std::vector<NamedScalar> state() const { return {}; }
  // Restores entries whose names the caller has checked against state(); throws
  // std::invalid_argument on a bad value, changing nothing then.
  virtual void restore_state(std::span<const NamedScalar> /*saved*/) {}
};

// The rule of `optimizer`: SGD and Adam with step size learning_rate (lambda_lr), PID with
// its options and initial integral max(initial_lambda, 1e-5).
std::unique_ptr<MultiplierRule> make_multiplier_rule(LambdaOptimizer optimizer, double learning_rate,
                                                     double initial_lambda, const PidLagrangianOptions& pid);

}  // namespace bsg::algos
