// The rows of BudgetKeys (common/budget_keys.h) in the key table, after the offline rows.
#include "common/budget_keys.h"

#include <vector>

#include "common/config_key_rows.h"

namespace bsg::key_rows {

// clang-format off
std::vector<ConfigKeyRow> budget_rows() {
  using L = ConfigLayer;
  using R = RunConfig;
  using N = NumericRange;
  using K = BudgetKeys;
  constexpr AlgorithmSet saute = algorithm_bit(Algorithm::ppo_saute) | algorithm_bit(Algorithm::trpo_saute);
  static_assert(keeps_saute_budgets(Algorithm::ppo_saute) && keeps_saute_budgets(Algorithm::trpo_saute));
  return {
    // --- budget methods (docs/algorithms.md#budget-methods) ---
    real("saute_gamma", field<&R::budget, &K::saute_gamma>(), L::algorithm, N::open(0, 1), saute,
         "Saute: gamma_s of the budget left, z_t+1 = (z_t - c_t / d~) / gamma_s with "
         "d~ = d (1 - gamma_s^T) / ((1 - gamma_s) T), T = max_ep_len"),
    real("unsafe_reward", field<&R::budget, &K::unsafe_reward>(), L::algorithm, N::any(), saute,
         "Saute: the learner's reward once some budget z_i is spent (<= 0); logs keep the environment's"),
  };
}
// clang-format on

}  // namespace bsg::key_rows
