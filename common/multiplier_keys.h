// MultiplierKeys: the configuration keys of the Lagrange multipliers of the
// Lagrangian algorithms (lag-trpo, pdo, ppo-lag, focops, cup and the off-policy
// -lag ones; docs/algorithms.md#lagrange-multipliers): the rule, its step size
// and the PID rule's gains. RunConfig holds them as `multiplier`; their rows
// in the key table are in multiplier_keys.cpp.
//
// Parameters (the member initialisers; a run takes its algorithm's from
// configs/algorithms/<alg>.yaml, see the rows for which algorithms a key applies to):
//   lagrangian_multiplier_init = 0.001, lambda_lr = 0.05, lambda_optimizer = SGD
//   lagrangian_upper_bound = 0 (none)                               focops
//   pid_kp = 0.1, pid_ki = 0.005, pid_kd = 0, pid_d_delay = 10,
//   pid_delta_p_ema_alpha = 0, pid_delta_d_ema_alpha = 0, pid_lambda_max = 0   lambda_optimizer PID
#pragma once

#include <array>
#include <string_view>

namespace bsg {

// Update rule of the Lagrange multiplier (docs/algorithms.md#trpo-l SGD for
// TRPO-L, docs/algorithms.md#pdo Adam for PDO; PID: the PID Lagrangian of Stooke, Achiam and Abbeel 2020, with
// the pid_* keys, algos/lagrange/pid_lagrangian.h).
enum class LambdaOptimizer { sgd, adam, pid };
inline constexpr std::array<std::string_view, 3> kLambdaOptimizerNames = {"SGD", "Adam", "PID"};

std::string_view to_string(LambdaOptimizer optimizer);

struct MultiplierKeys {
  double lagrangian_multiplier_init = 0.001;
  double lambda_lr = 0.05;
  LambdaOptimizer lambda_optimizer = LambdaOptimizer::sgd;
  double lagrangian_upper_bound = 0.0;  // FOCOPS's nu_max (every rule); 0 = none
  // PID multiplier (lambda_optimizer PID only; algos/lagrange/pid_lagrangian.h)
  double pid_kp = 0.1;                  // K_P
  double pid_ki = 0.005;                // K_I (replaces lambda_lr)
  double pid_kd = 0.0;                  // K_D
  int pid_d_delay = 10;                 // epochs between the J_ema compared by D
  double pid_delta_p_ema_alpha = 0.0;   // EMA factor of the P input; 0 = none
  double pid_delta_d_ema_alpha = 0.0;   // EMA factor of the D input; 0 = none
  double pid_lambda_max = 0.0;          // upper bound on lambda; 0 = none

  bool operator==(const MultiplierKeys&) const = default;
};

}  // namespace bsg
