// OfflineKeys: the configuration keys of the offline family (bc-all, bc-safe;
// docs/datasets.md#offline-runs): the dataset a run learns from, its gradient
// steps per epoch and how often it is evaluated online. RunConfig holds them as
// `offline`; their rows in the key table are in offline_keys.cpp. The family
// also reads keys of other groups whose meaning it shares: actor_lr
// (FirstOrderKeys, the policy's Adam step size), batch_size (OffPolicyKeys,
// rows per gradient step), and RunConfig's hidden_sizes, activation,
// zero_bias_init, dtype, cost_limit (BC-Safe's episodes), epochs,
// eval_episodes, save_freq and seed.
//
// CPQ (algos/offline/cpq.h), BCQ-Lag (algos/offline/bcq_lag.h) and COptiDICE
// (algos/offline/coptidice.h) read their own keys here (the VAE's and the scales
// shared) and, of other groups, gamma, critic_lr and (CPQ, BCQ-Lag) polyak.
//
// Parameters (the member initialisers; a run takes its algorithm's from
// configs/algorithms/<alg>.yaml):
//   dataset = "" (required), updates_per_epoch = 200, eval_every = 1
//   reward_scale = 0.1, cost_scale = 1, vae_lr = 0.001, vae_kl_weight = 0.5,
//   vae_hidden_size = 400, cpq_sampled_actions = 10, cpq_qc_scalar = 1.5,
//   cpq_alpha_lr = 0.0001                                            cpq
//   bcq_phi = 0.05, bcq_lambda = 0.75, bcq_sampled_actions = 10,
//   bcq_pid_kp = 0.1, bcq_pid_ki = 0.003, bcq_pid_kd = 0.001         bcq-lag
//   coptidice_alpha = 0.5, coptidice_cost_ub_epsilon = 0.01,
//   coptidice_f_divergence = softchi, coptidice_scalar_lr = 0.0001    coptidice
#pragma once

#include <array>
#include <string>
#include <string_view>

namespace bsg {

// COptiDICE's f-divergence between the policy's stationary distribution and the data's (OSRL's f_type).
enum class FDivergence { chi2, softchi, kl };
inline constexpr std::array<std::string_view, 3> kFDivergenceNames = {"chi2", "softchi", "kl"};

std::string_view to_string(FDivergence f);

struct OfflineKeys {
  std::string dataset;          // the HDF5 file (DSRL's layout) the policy learns from
  int updates_per_epoch = 200;  // gradient steps per epoch
  int eval_every = 1;           // online evaluation after every eval_every-th epoch (and the last)
  double reward_scale = 0.1;    // CPQ: rewards times reward_scale in the critics' targets
  double cost_scale = 1.0;      // CPQ: costs times cost_scale in the cost critics' targets
  double vae_lr = 0.001;        // CPQ: Adam step size of the behaviour VAE
  double vae_kl_weight = 0.5;   // CPQ: beta, the weight of the VAE's KL term
  int vae_hidden_size = 400;    // CPQ: units of each of the VAE's two hidden layers (encoder and decoder)
  int cpq_sampled_actions = 10;   // CPQ: policy actions sampled per row for the out-of-distribution term
  double cpq_qc_scalar = 1.5;     // CPQ: the out-of-distribution cost is pushed above qc_scalar times l
  double cpq_alpha_lr = 0.0001;   // CPQ: step size of log alpha, the out-of-distribution multiplier
  double bcq_phi = 0.05;          // BCQ-Lag: the perturbation's bound, |a - a_hat| <= phi
  double bcq_lambda = 0.75;       // BCQ-Lag: weight of the min of the two heads in the soft clipped double Q
  int bcq_sampled_actions = 10;   // BCQ-Lag: VAE proposals per next observation in the critics' targets
  double bcq_pid_kp = 0.1;        // BCQ-Lag: OSRL's PID controller on the cost critic's estimate, K_P
  double bcq_pid_ki = 0.003;      // BCQ-Lag: K_I
  double bcq_pid_kd = 0.001;      // BCQ-Lag: K_D
  double coptidice_alpha = 0.5;             // COptiDICE: weight of the f-divergence in the dual
  double coptidice_cost_ub_epsilon = 0.01;  // COptiDICE: KL budget of the cost upper bound; 0 = plain estimate
  FDivergence coptidice_f_divergence = FDivergence::softchi;  // COptiDICE: f
  double coptidice_scalar_lr = 0.0001;      // COptiDICE: Adam step size of lambda and tau

  bool operator==(const OfflineKeys&) const = default;
};

}  // namespace bsg
