// FirstOrderKeys: the configuration keys of the first-order family (ppo,
// ppo-lag, focops, cup, p3o, ipo; docs/algorithms.md#first-order-updates): Adam on the
// policy, minibatch passes with their KL early stop, gradient clipping, and the
// variants' own keys (PPO's clip, FOCOPS's lambda and eta, P3O's and IPO's kappa). actor_lr and
// max_grad_norm serve the off-policy learners too. RunConfig holds them as
// `first_order`; their rows in the key table are in first_order_keys.cpp.
//
// Parameters (the member initialisers; a run takes its algorithm's from
// configs/algorithms/<alg>.yaml, see the rows for which algorithms a key applies to):
//   actor_lr = 3e-4, update_iters = 40, policy_minibatch_size = 64,
//   kl_early_stop = true, max_grad_norm = 40
//   clip = 0.2                                       ppo, ppo-lag, cup, p3o, ipo
//   focops_lam = 1.5, focops_eta = 0.02              focops
//   p3o_kappa = 20, p3o_cost_clip = true             p3o
//   ipo_kappa = 0.01, ipo_penalty_max = 1            ipo
//   learn_log_std = false, learned_std_init = 0.509
#pragma once

namespace bsg {

struct FirstOrderKeys {
  double actor_lr = 3e-4;          // Adam step size on the policy
  int update_iters = 40;           // passes over the batch per update
  int policy_minibatch_size = 64;  // samples per minibatch, summed over ranks
  bool kl_early_stop = true;       // stop the passes once the KL exceeds target_kl
  double max_grad_norm = 40.0;     // 0: no gradient rescaling
  double clip = 0.2;               // PPO's epsilon (ppo, ppo-lag, cup's first step, p3o, ipo)
  double focops_lam = 1.5;         // FOCOPS's temperature lambda
  double focops_eta = 0.02;        // FOCOPS's per-sample KL mask threshold
  double p3o_kappa = 20.0;         // P3O's penalty factor kappa on ReLU(L_C + J_C - d)
  bool p3o_cost_clip = true;       // P3O's cost surrogate clipped (the paper) or not (OmniSafe's p3o.py)
  double ipo_kappa = 0.01;         // IPO's barrier coefficient kappa = 1/t
  double ipo_penalty_max = 1.0;    // IPO's largest penalty, taken whenever J_C >= d
  bool learn_log_std = false;      // learn a state-independent log sigma per action dimension
  double learned_std_init = 0.509; // its initial sigma (the annealing's first)

  bool operator==(const FirstOrderKeys&) const = default;
};

}  // namespace bsg
