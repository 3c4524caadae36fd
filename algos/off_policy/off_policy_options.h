// What the off-policy learners read from the RunConfig (docs/algorithms.md#networks-and-the-gradient-step).
// The learner's kind (SAC, TD3, DDPG: which actor, how many reward critics, smoothing) is its class
// (make_off_policy_learner.h), not an option.
#pragma once

#include <vector>

#include "common/mlp.h"
#include "common/run_config.h"

namespace bsg::algos {

struct OffPolicyOptions {
  int policy_delay = 1;            // actor, temperature and targets every policy_delay critic steps
  double gamma = 0.99;             // only for reporting; the discounts come with the batch
  double polyak = 0.005;
  double actor_lr = 3e-4;
  double critic_lr = 1e-3;
  double exploration_noise = 0.1;  // deterministic actors while collecting
  double policy_noise = 0.2;       // TD3's target smoothing
  double noise_clip = 0.5;
  double alpha_init = 0.2;         // SAC's temperature
  bool auto_alpha = false;
  double alpha_lr = 3e-4;
  double target_entropy = -1.0;    // -|A|
  double max_grad_norm = 0.0;      // 0: gradients are not rescaled
  std::vector<int> hidden_sizes{64, 64};
  MlpOptions mlp{};

  // Throws std::invalid_argument if config.alg is not an off-policy algorithm.
  static OffPolicyOptions from_config(const RunConfig& config, int action_size);
};

}  // namespace bsg::algos
