// OffPolicyKeys: the configuration keys of the off-policy family (sac, td3,
// ddpg and their -lag forms; docs/algorithms.md#off-policy-learners): acting
// in num_envs environments, the replay buffer, the gradient steps and each
// learner's own keys (TD3's smoothing, SAC's temperature). RunConfig holds them
// as `off_policy`; their rows in the key table are in off_policy_keys.cpp. The
// learners read them through algos::OffPolicyOptions::from_config
// (algos/off_policy/off_policy_options.h), with actor_lr and max_grad_norm
// of FirstOrderKeys.
//
// Parameters (the member initialisers; a run takes its algorithm's from
// configs/algorithms/<alg>.yaml, see the rows for which algorithms a key applies to):
//   num_envs = 1, start_steps = 10000, update_every = 1, updates_per_step = 1,
//   batch_size = 256, buffer_size = 1000000, polyak = 0.005, n_step = 1,
//   critic_lr = 0.001, policy_delay = 2
//   exploration_noise = 0.1                          td3, ddpg
//   policy_noise = 0.2, noise_clip = 0.5             td3
//   alpha_init = 0.2, auto_alpha = false, alpha_lr = 0.0003   sac
//   multiplier_schedule = epoch, multiplier_window = 10        sac-lag, td3-lag, ddpg-lag
#pragma once

#include <array>
#include <string_view>

namespace bsg {

// When an off-policy -lag run steps its Lagrange multipliers
// (docs/algorithms.md#when-the-off-policy-multipliers-step): once per epoch on the epoch's
// episodes, or before every round of gradient steps on the last multiplier_window episodes
// (OmniSafe steps in every update, FSRL before every round of updates).
enum class MultiplierSchedule { epoch, update_round };
inline constexpr std::array<std::string_view, 2> kMultiplierScheduleNames = {"epoch", "update_round"};

struct OffPolicyKeys {
  int num_envs = 1;                // environments per rank, stepped in turn
  int start_steps = 10000;         // uniform random actions for the first start_steps steps (all ranks)
  int update_every = 1;            // environment steps (per rank, over its environments) between rounds of updates
  double updates_per_step = 1.0;   // gradient steps per environment step of a rank
  int batch_size = 256;            // transitions per gradient step and rank
  int buffer_size = 1000000;       // replay buffer capacity in transitions per rank
  double polyak = 0.005;           // tau: target <- (1 - tau) target + tau online
  int n_step = 1;                  // n-step returns
  double critic_lr = 0.001;        // Adam step size of the Q networks
  double exploration_noise = 0.1;  // TD3, DDPG: std of the Gaussian action noise
  double policy_noise = 0.2;       // TD3: std of the target policy smoothing noise
  double noise_clip = 0.5;         // TD3: the smoothing noise is clipped to +-noise_clip
  int policy_delay = 2;            // TD3: critic steps per actor (and target) step
  double alpha_init = 0.2;         // SAC: initial entropy temperature
  bool auto_alpha = false;         // SAC: learn alpha towards the target entropy -|A|
  double alpha_lr = 0.0003;        // SAC: Adam step size of log alpha
  MultiplierSchedule multiplier_schedule = MultiplierSchedule::epoch;  // -lag: when the multipliers step
  int multiplier_window = 10;      // -lag, update_round: episodes (per rank) in the cost a step sees

  bool operator==(const OffPolicyKeys&) const = default;
};

}  // namespace bsg
