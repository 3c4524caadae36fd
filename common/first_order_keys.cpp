// The rows of FirstOrderKeys (common/first_order_keys.h) in the key table,
// after the trust-region variants' rows. A first-order variant's own key is a
// member of FirstOrderKeys and a row here applying to algorithm_bit(Algorithm::<its name>).
#include "common/first_order_keys.h"

#include <vector>

#include "common/config_key_rows.h"

namespace bsg::key_rows {

namespace {
constexpr AlgorithmSet kClipped = algorithms_where(&AlgorithmInfo::clipped_surrogate);
}  // namespace

// clang-format off
std::vector<ConfigKeyRow> first_order_rows() {
  using L = ConfigLayer;
  using R = RunConfig;
  using N = NumericRange;
  using K = FirstOrderKeys;
  return {
    // --- first-order updates (docs/algorithms.md#first-order-updates) ---
    real("actor_lr", field<&R::first_order, &K::actor_lr>(), L::algorithm, N::above(0), kFirstOrder | kOffPolicy | kOffline | kMultiAgentFirstOrder,
         "Adam step size on the policy (first-order and off-policy updates)"),
    integer("update_iters", field<&R::first_order, &K::update_iters>(), L::algorithm, N::closed(1, 10000), kFirstOrder | kMultiAgentFirstOrder,
            "passes over the batch per policy update (fewer after a KL early stop)"),
    integer("policy_minibatch_size", field<&R::first_order, &K::policy_minibatch_size>(), L::algorithm, N::closed(1, kIntMax), kFirstOrder | kMultiAgentFirstOrder,
            "samples per policy minibatch, summed over ranks: floor(B / size) minibatches per pass"),
    boolean("kl_early_stop", field<&R::first_order, &K::kl_early_stop>(), L::algorithm, kFirstOrder,
            "end the passes after one whose mean KL to the update's start exceeds target_kl"),
    real("max_grad_norm", field<&R::first_order, &K::max_grad_norm>(), L::algorithm, N::at_least(0), kFirstOrder | kOffPolicy | kMultiAgentFirstOrder,
         "rescale the rank-averaged gradient of each step (first-order: the policy's; off-policy: the twin "
         "reward critics' together, each cost critic's, the actor's) to at most this norm; 0 = never"),
    real("clip", field<&R::first_order, &K::clip>(), L::algorithm, N::open(0, 1), kClipped,
         "epsilon of PPO's clipped surrogate (ppo, ppo-lag, cup's performance step)"),
    real("focops_lam", field<&R::first_order, &K::focops_lam>(), L::algorithm, N::above(0), algorithm_bit(Algorithm::focops),
         "FOCOPS's temperature lambda: the loss is KL - rho (A - nu A^C) / lambda"),
    real("focops_eta", field<&R::first_order, &K::focops_eta>(), L::algorithm, N::above(0), algorithm_bit(Algorithm::focops),
         "FOCOPS's mask: samples whose KL to the old policy exceeds eta leave the loss"),
    real("p3o_kappa", field<&R::first_order, &K::p3o_kappa>(), L::algorithm, N::above(0), algorithm_bit(Algorithm::p3o),
         "P3O's penalty factor: the loss adds kappa sum_j ReLU(L_Cj + J_Cj - d_j) to PPO's"),
    boolean("p3o_cost_clip", field<&R::first_order, &K::p3o_cost_clip>(), L::algorithm, algorithm_bit(Algorithm::p3o),
            "P3O's cost surrogate L_C = mean max(rho A^C, clip(rho) A^C) (the paper); false: mean rho A^C (OmniSafe)"),
    real("ipo_kappa", field<&R::first_order, &K::ipo_kappa>(), L::algorithm, N::above(0), algorithm_bit(Algorithm::ipo),
         "IPO's barrier coefficient kappa = 1/t: the penalty on A^C is kappa / (d - J_C)"),
    real("ipo_penalty_max", field<&R::first_order, &K::ipo_penalty_max>(), L::algorithm, N::above(0), algorithm_bit(Algorithm::ipo),
         "IPO's largest penalty on A^C, taken when kappa / (d - J_C) exceeds it or J_C >= d"),
    boolean("learn_log_std", field<&R::first_order, &K::learn_log_std>(), L::algorithm, kFirstOrder,
            "learn a log sigma per action dimension with the policy's Adam (replaces the annealed sigma)"),
    real("learned_std_init", field<&R::first_order, &K::learned_std_init>(), L::algorithm, N::above(0), kFirstOrder | kMultiAgent,
         "initial sigma of every dimension with learn_log_std"),
  };
}
// clang-format on

}  // namespace bsg::key_rows
