// BudgetKeys: the keys of the budget methods, PPO and TRPO on an environment whose budget
// decorator changes what the learner sees (docs/algorithms.md#budget-methods): Saute's
// discount of the budget and the reward once it is spent. RunConfig holds them as `budget`;
// their rows are in budget_keys.cpp. The budgets themselves are the constraints' limits
// (cost_limit, or each limit of `constraints:`), as OmniSafe's safety_budget and cost_limit
// equal the cost limit.
//
// Parameters (the member initialisers; a run takes its algorithm's from
// configs/algorithms/<alg>.yaml): saute_gamma = 0.999, unsafe_reward = -1 (OmniSafe's
// PPOSaute.yaml and TRPOSaute.yaml).
#pragma once

#include "common/algorithms.h"

namespace bsg {

// Whether `alg` keeps Saute budgets (each limit is then divided by, so it must be positive).
constexpr bool keeps_saute_budgets(Algorithm alg) { return alg == Algorithm::ppo_saute || alg == Algorithm::trpo_saute; }

struct BudgetKeys {
  double saute_gamma = 0.999;   // gamma_s of the budget update z_t+1 = (z_t - c_t / d~) / gamma_s
  double unsafe_reward = -1.0;  // the learner's reward once a budget is spent

  bool operator==(const BudgetKeys&) const = default;
};

}  // namespace bsg
