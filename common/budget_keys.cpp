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
  constexpr AlgorithmSet simmer = algorithm_bit(Algorithm::ppo_simmer) | algorithm_bit(Algorithm::trpo_simmer);
  constexpr AlgorithmSet saute = algorithm_bit(Algorithm::ppo_saute) | algorithm_bit(Algorithm::trpo_saute) | simmer;
  static_assert(keeps_saute_budgets(Algorithm::ppo_saute) && keeps_saute_budgets(Algorithm::trpo_saute));
  static_assert(schedules_saute_budgets(Algorithm::ppo_simmer) && schedules_saute_budgets(Algorithm::trpo_simmer));
  return {
    // --- budget methods (docs/algorithms.md#budget-methods) ---
    real("saute_gamma", field<&R::budget, &K::saute_gamma>(), L::algorithm, N::open(0, 1), saute,
         "Saute: gamma_s of the budget left, z_t+1 = (z_t - c_t / d~) / gamma_s with "
         "d~ = d (1 - gamma_s^T) / ((1 - gamma_s) T), T = max_ep_len"),
    real("unsafe_reward", field<&R::budget, &K::unsafe_reward>(), L::algorithm, N::any(), saute,
         "Saute: the learner's reward once some budget z_i is spent (<= 0); logs keep the environment's"),
    real("simmer_kp", field<&R::budget, &K::simmer_kp>(), L::algorithm, N::at_least(0), simmer,
         "Simmer: K_P of the budget's PID controller on the smoothed error e_k, in units of d~"),
    real("simmer_ki", field<&R::budget, &K::simmer_ki>(), L::algorithm, N::at_least(0), simmer,
         "Simmer: K_I on the sum of the last 10 smoothed errors"),
    real("simmer_kd", field<&R::budget, &K::simmer_kd>(), L::algorithm, N::at_least(0), simmer,
         "Simmer: K_D on the last epoch's clipped minus unclipped budget step"),
    real("simmer_polyak", field<&R::budget, &K::simmer_polyak>(), L::algorithm, N::closed_open(0, 1), simmer,
         "Simmer: smoothing of the error, e_k = p e_k-1 + (1 - p) (d~_k - J~_k), J~ the epoch's mean "
         "episode cost scaled like d~"),
    real("simmer_initial_budget_fraction", field<&R::budget, &K::simmer_initial_budget_fraction>(), L::algorithm,
         N::open_closed(0, 1), simmer,
         "Simmer: the first epoch's budget as a fraction of the limit d, which is also the budget's ceiling"),
  };
}
// clang-format on

}  // namespace bsg::key_rows
