// The Lagrange multiplier lambda >= 0 of TRPO-L (docs/algorithms.md#trpo-l) and PDO (docs/algorithms.md#pdo).
// Its loss is -lambda (J_C - d), so d loss / d lambda = -(J_C - d); one step of
// the configured optimiser per epoch, then lambda is clamped at 0 (after the
// step; Adam's moments are kept, not reset, by the clamp).
//   SGD:  lambda <- max(0, lambda + alpha_lambda (J_C - d))
//   Adam: lambda <- max(0, Adam step on gradient -(J_C - d))
//   PID:  lambda = max(0, P + I + D), the PID Lagrangian (pid_lagrangian.h);
//         its integral with gain K_I is the SGD rule with alpha_lambda = K_I
// The update uses only the pooled J_C, so every rank computes the same lambda
// without communication (docs/algorithms.md#across-mpi-ranks).
//
// Parameters:
//   initial_value   lagrangian_multiplier_init, 0.001; the original uses max(init, 1e-5)
//   optimizer       lambda_optimizer: SGD (TRPO-L), Adam (PDO, beta 0.9/0.999, eps 1e-8) or PID
//   learning_rate   lambda_lr: alpha_lambda (SGD, Adam)
//   pid             the pid_* keys (PID only)
//   upper_bound     lagrangian_upper_bound (FOCOPS's nu_max, any rule): lambda <- min(lambda, bound)
//                   after the update; 0 (every other algorithm): none
#pragma once

#include <memory>
#include <span>
#include <string>
#include <vector>

#include "algos/core/algorithm.h"
#include "algos/lagrange/multiplier_rule.h"
#include "algos/lagrange/pid_lagrangian.h"
#include "common/run_config.h"

namespace bsg::algos {

class LagrangeMultiplier {
 public:
  LagrangeMultiplier(double initial_value, LambdaOptimizer optimizer, double learning_rate,
                     const PidLagrangianOptions& pid = {});
  // From lagrangian_multiplier_init, lambda_optimizer, lambda_lr and the pid_* keys.
  explicit LagrangeMultiplier(const RunConfig& config);
  // A copy has its own rule state (LagrangeMultipliers validates a restore on copies).
  LagrangeMultiplier(const LagrangeMultiplier& other);
  LagrangeMultiplier& operator=(const LagrangeMultiplier& other);
  LagrangeMultiplier(LagrangeMultiplier&&) noexcept = default;
  LagrangeMultiplier& operator=(LagrangeMultiplier&&) noexcept = default;
  ~LagrangeMultiplier() = default;

  double value() const { return lambda_; }
  LambdaOptimizer optimizer() const { return optimizer_; }

  // One step of the rule on the loss -lambda (J_C - d) (lambda >= 0 after it), then the
  // upper bound if any; returns the new lambda.
  double update(double mean_episode_cost, double cost_limit);

  // The progress columns of the multiplier: "LagrangeMultiplier", then the rule's
  // (PID: its terms after the last update "PID/P", "PID/I", "PID/D").
  std::vector<std::string> diagnostic_names() const;
  std::vector<NamedScalar> diagnostics() const;

  // "lagrange_multiplier", then the rule's entries (Adam: "lagrange_multiplier_adam_m",
  // "..._v", "..._t"; PID: PidLagrangian::state()'s entries).
  std::vector<NamedScalar> state() const;
  // Throws std::invalid_argument if the names differ from state()'s or lambda < 0.
  void restore_state(std::span<const NamedScalar> saved);

 private:
  double lambda_;
  LambdaOptimizer optimizer_;
  std::unique_ptr<MultiplierRule> rule_;  // the lambda_optimizer's step and its state
  double upper_bound_ = 0.0;  // lagrangian_upper_bound (FOCOPS's nu_max); 0: none
};

}  // namespace bsg::algos
