// BudgetKeys: the keys of the budget methods, PPO and TRPO on an environment whose budget
// decorator changes what the learner sees (docs/algorithms.md#budget-methods): Saute's
// discount of the budget and the reward once it is spent, and Simmer's PID controller of the
// budget (algos/training/simmer_budget_controller.h). RunConfig holds them as `budget`;
// their rows are in budget_keys.cpp. The budgets themselves are the constraints' limits
// (cost_limit, or each limit of `constraints:`), as OmniSafe's safety_budget and cost_limit
// equal the cost limit.
//
// Parameters (the member initialisers; a run takes its algorithm's from
// configs/algorithms/<alg>.yaml): saute_gamma = 0.999, unsafe_reward = -1 (OmniSafe's
// PPOSaute.yaml and TRPOSaute.yaml); simmer_kp = 0.0005, simmer_ki = 0.00001, simmer_kd = 0,
// simmer_polyak = 0.995 (the control_cfgs of OmniSafe's PPOSimmerPID.yaml and TRPOSimmerPID.yaml),
// simmer_initial_budget_fraction = 1 (their safety_budget equals their upper_budget, 25).
#pragma once

#include "common/algorithms.h"

namespace bsg {

// Whether `alg` schedules its Saute budgets with Simmer's controller.
constexpr bool schedules_saute_budgets(Algorithm alg) {
  return alg == Algorithm::ppo_simmer || alg == Algorithm::trpo_simmer;
}

// Whether `alg` keeps Saute budgets (each limit is then divided by, so it must be positive).
constexpr bool keeps_saute_budgets(Algorithm alg) {
  return alg == Algorithm::ppo_saute || alg == Algorithm::trpo_saute || schedules_saute_budgets(alg);
}

struct BudgetKeys {
  double saute_gamma = 0.999;   // gamma_s of the budget update z_t+1 = (z_t - c_t / d~) / gamma_s
  double unsafe_reward = -1.0;  // the learner's reward once a budget is spent
  // Simmer's controller, in the units of d~ (its error is d~_k - J~_k, both scaled like d~).
  double simmer_kp = 0.0005;    // K_P on the smoothed error
  double simmer_ki = 0.00001;   // K_I on the sum of the last 10 smoothed errors
  double simmer_kd = 0.0;       // K_D on the last step's clipping, b_k - b_k-1 minus the unclipped step
  double simmer_polyak = 0.995;  // smoothing of the error, e_k = p e_k-1 + (1 - p) (d~_k - J~_k)
  double simmer_initial_budget_fraction = 1.0;  // b_0 = fraction d, the limit d also the budget's ceiling

  bool operator==(const BudgetKeys&) const = default;
};

}  // namespace bsg
