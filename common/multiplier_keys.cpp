// The rows of MultiplierKeys (common/multiplier_keys.h) in the key table,
// between the trust-region tools' rows and the trust-region variants'. A new
// multiplier rule's keys are members of MultiplierKeys and rows here applying
// to kLagrangian.
#include "common/multiplier_keys.h"

#include <vector>

#include "common/config_key_rows.h"

namespace bsg {

std::string_view to_string(LambdaOptimizer optimizer) {
  return key_rows::enum_name(kLambdaOptimizerNames, optimizer);
}

namespace key_rows {

// clang-format off
std::vector<ConfigKeyRow> multiplier_rows() {
  using L = ConfigLayer;
  using R = RunConfig;
  using N = NumericRange;
  using K = MultiplierKeys;
  return {
    // --- Lagrange multiplier (docs/algorithms.md#trpo-l, #pdo) ---
    real("lagrangian_multiplier_init", field<&R::multiplier, &K::lagrangian_multiplier_init>(), L::algorithm,
         N::at_least(0), kLagrangian, "initial Lagrange multiplier lambda (PID: the initial integral I)"),
    real("lambda_lr", field<&R::multiplier, &K::lambda_lr>(), L::algorithm, N::above(0), kLagrangian,
         "alpha_lambda: learning rate of the Lagrange multiplier (SGD, Adam; PID uses pid_ki)"),
    choice("lambda_optimizer", enum_access<&R::multiplier, &K::lambda_optimizer>(), kLambdaOptimizerNames,
           L::algorithm, kLagrangian,
           "update rule of the Lagrange multiplier: SGD or Adam step of lambda_lr on "
           "-lambda (J_C - d), or PID (Stooke et al. 2020) with the pid_* keys"),
    real("lagrangian_upper_bound", field<&R::multiplier, &K::lagrangian_upper_bound>(), L::algorithm, N::at_least(0),
         algorithm_bit(Algorithm::focops),
         "FOCOPS's nu_max: each multiplier is projected onto [0, nu_max] after its update; 0 = no bound"),
    // --- PID Lagrange multiplier (lambda_optimizer PID; algos/lagrange/pid_lagrangian.h) ---
    real("pid_kp", field<&R::multiplier, &K::pid_kp>(), L::algorithm, N::at_least(0), kLagrangian,
         "PID only: K_P, proportional gain on the (smoothed) violation J_C - d"),
    real("pid_ki", field<&R::multiplier, &K::pid_ki>(), L::algorithm, N::at_least(0), kLagrangian,
         "PID only: K_I, integral gain, I <- max(0, I + K_I (J_C - d)) (the SGD rule's lambda_lr)"),
    real("pid_kd", field<&R::multiplier, &K::pid_kd>(), L::algorithm, N::at_least(0), kLagrangian,
         "PID only: K_D, derivative gain on the cost rise max(0, J_ema - J_ema[k - pid_d_delay])"),
    integer("pid_d_delay", field<&R::multiplier, &K::pid_d_delay>(), L::algorithm, N::closed(1, 1000), kLagrangian,
            "PID only: epochs between the two smoothed costs the derivative compares"),
    real("pid_delta_p_ema_alpha", field<&R::multiplier, &K::pid_delta_p_ema_alpha>(), L::algorithm, N::closed_open(0, 1),
         kLagrangian, "PID only: EMA factor a of the P input, x <- a x + (1 - a) (J_C - d); 0 = none"),
    real("pid_delta_d_ema_alpha", field<&R::multiplier, &K::pid_delta_d_ema_alpha>(), L::algorithm, N::closed_open(0, 1),
         kLagrangian, "PID only: EMA factor a of the D input, J_ema <- a J_ema + (1 - a) J_C; 0 = none"),
    real("pid_lambda_max", field<&R::multiplier, &K::pid_lambda_max>(), L::algorithm, N::at_least(0), kLagrangian,
         "PID only: upper bound on lambda; 0 = no bound"),
  };
}
// clang-format on

}  // namespace key_rows
}  // namespace bsg
