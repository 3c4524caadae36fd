// The rows of OffPolicyKeys (common/off_policy_keys.h) in the key table, after
// the first-order rows. An off-policy learner's own key is a member of
// OffPolicyKeys and a row here applying to its algorithms (as kSacFamily,
// kTd3Family), read into algos::OffPolicyOptions::from_config.
#include "common/off_policy_keys.h"

#include <vector>

#include "common/config_key_rows.h"

namespace bsg::key_rows {

namespace {
constexpr AlgorithmSet kSacFamily = algorithm_bit(Algorithm::sac) | algorithm_bit(Algorithm::sac_lag);
constexpr AlgorithmSet kTd3Family = algorithm_bit(Algorithm::td3) | algorithm_bit(Algorithm::td3_lag);
constexpr AlgorithmSet kDeterministicActor =
    kTd3Family | algorithm_bit(Algorithm::ddpg) | algorithm_bit(Algorithm::ddpg_lag);
constexpr AlgorithmSet kOffPolicyLagrangian = kOffPolicy & kLagrangian;
}  // namespace

// clang-format off
std::vector<ConfigKeyRow> off_policy_rows() {
  using L = ConfigLayer;
  using R = RunConfig;
  using N = NumericRange;
  using K = OffPolicyKeys;
  return {
    // --- off-policy learners (docs/algorithms.md#off-policy-learners) ---
    integer("num_envs", field<&R::off_policy, &K::num_envs>(), L::algorithm, N::closed(1, 4096), kOffPolicy,
            "environments per rank, stepped in turn; steps_per_epoch / ranks must be a multiple of it"),
    integer("start_steps", field<&R::off_policy, &K::start_steps>(), L::algorithm, N::closed(0, kIntMax), kOffPolicy,
            "uniform random actions for the first start_steps environment steps (summed over ranks); "
            "gradient steps begin after them"),
    integer("update_every", field<&R::off_policy, &K::update_every>(), L::algorithm, N::closed(1, kIntMax), kOffPolicy,
            "environment steps of a rank between rounds of gradient steps"),
    real("updates_per_step", field<&R::off_policy, &K::updates_per_step>(), L::algorithm, N::open_closed(0, 1000), kOffPolicy,
         "gradient steps per environment step of a rank (a round of update_every steps takes "
         "update_every * updates_per_step of them, fractions carried to the next round)"),
    integer("batch_size", field<&R::off_policy, &K::batch_size>(), L::algorithm, N::closed(1, 1000000), kOffPolicy | kOffline,
            "transitions per gradient step, sampled uniformly from the rank's replay buffer"),
    integer("buffer_size", field<&R::off_policy, &K::buffer_size>(), L::algorithm, N::closed(1, kIntMax), kOffPolicy,
            "replay buffer capacity in transitions per rank (the oldest are overwritten)"),
    real("polyak", field<&R::off_policy, &K::polyak>(), L::algorithm, N::open_closed(0, 1),
         kOffPolicy | algorithm_bit(Algorithm::cpq) | algorithm_bit(Algorithm::bcq_lag),
         "tau: target nets <- (1 - tau) target + tau online after each critic (TD3: actor) step"),
    integer("n_step", field<&R::off_policy, &K::n_step>(), L::algorithm, N::closed(1, 1000), kOffPolicy,
            "n-step returns: sum of n discounted rewards, then gamma^n Q of the n-th next state"),
    real("critic_lr", field<&R::off_policy, &K::critic_lr>(), L::algorithm, N::above(0),
         kOffPolicy | algorithm_bit(Algorithm::cpq) | algorithm_bit(Algorithm::bcq_lag) | algorithm_bit(Algorithm::coptidice),
         "Adam step size of the reward and cost Q networks"),
    real("exploration_noise", field<&R::off_policy, &K::exploration_noise>(), L::algorithm, N::at_least(0), kDeterministicActor,
         "std of the Gaussian noise on the deterministic actor's actions while collecting"),
    real("policy_noise", field<&R::off_policy, &K::policy_noise>(), L::algorithm, N::at_least(0), kTd3Family,
         "TD3: std of the target policy smoothing noise"),
    real("noise_clip", field<&R::off_policy, &K::noise_clip>(), L::algorithm, N::at_least(0), kTd3Family,
         "TD3: the smoothing noise is clipped to +-noise_clip"),
    integer("policy_delay", field<&R::off_policy, &K::policy_delay>(), L::algorithm, N::closed(1, 1000), kOffPolicy,
            "critic steps per actor, temperature and target step (TD3's delay; OmniSafe delays SAC's too)"),
    real("alpha_init", field<&R::off_policy, &K::alpha_init>(), L::algorithm, N::above(0), kSacFamily,
         "SAC: initial entropy temperature alpha"),
    boolean("auto_alpha", field<&R::off_policy, &K::auto_alpha>(), L::algorithm, kSacFamily,
            "SAC: learn log alpha towards the target entropy -|A| (false: alpha stays alpha_init)"),
    real("alpha_lr", field<&R::off_policy, &K::alpha_lr>(), L::algorithm, N::above(0), kSacFamily,
         "SAC: Adam step size of log alpha (auto_alpha)"),
    choice("multiplier_schedule", enum_access<&R::off_policy, &K::multiplier_schedule>(), kMultiplierScheduleNames,
           L::algorithm, kOffPolicyLagrangian,
           "when the Lagrange multipliers step: epoch (once, on the epoch's episodes) or update_round "
           "(before every round of gradient steps, on the last multiplier_window episodes)"),
    integer("multiplier_window", field<&R::off_policy, &K::multiplier_window>(), L::algorithm, N::closed(1, 1000000),
            kOffPolicyLagrangian,
            "update_round: the multipliers' cost is the mean of each rank's last multiplier_window episodes"),
  };
}
// clang-format on

}  // namespace bsg::key_rows
