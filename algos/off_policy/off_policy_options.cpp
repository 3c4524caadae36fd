#include "algos/off_policy/off_policy_options.h"

#include <stdexcept>
#include <string>

#include "common/algorithms.h"

namespace bsg::algos {

OffPolicyOptions OffPolicyOptions::from_config(const RunConfig& config, int action_size) {
  if (!is_off_policy(config.alg)) {
    throw std::invalid_argument("OffPolicyOptions: " + std::string(to_string(config.alg)) +
                                " is not an off-policy algorithm");
  }
  OffPolicyOptions options;
  options.policy_delay = config.off_policy.policy_delay;
  options.gamma = config.gamma;
  options.polyak = config.off_policy.polyak;
  options.actor_lr = config.first_order.actor_lr;
  options.critic_lr = config.off_policy.critic_lr;
  options.exploration_noise = config.off_policy.exploration_noise;
  options.policy_noise = config.off_policy.policy_noise;
  options.noise_clip = config.off_policy.noise_clip;
  options.alpha_init = config.off_policy.alpha_init;
  options.auto_alpha = config.off_policy.auto_alpha;
  options.alpha_lr = config.off_policy.alpha_lr;
  options.target_entropy = -static_cast<double>(action_size);  // Haarnoja et al. 2018b: -dim(A)
  options.max_grad_norm = config.first_order.max_grad_norm;
  options.hidden_sizes = config.hidden_sizes;
  options.mlp = MlpOptions{.zero_bias_init = config.zero_bias_init, .dtype = config.dtype, .activation = config.activation};
  return options;
}

}  // namespace bsg::algos
