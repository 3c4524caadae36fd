#include "algos/offline/make_offline_algorithm.h"

#include <stdexcept>
#include <string>

#include "algos/offline/bcq_lag.h"
#include "algos/offline/behaviour_cloning.h"
#include "algos/offline/cpq.h"

namespace bsg::algos {
namespace {

[[noreturn]] void not_offline(const RunConfig& config) {
  throw std::invalid_argument("offline algorithm: " + std::string(to_string(config.alg)) + " is not offline");
}

// What every learner with critics reads alike: its networks, gamma, the step sizes of actor and
// critics, the scales, the limit and T.
template <typename Options>
Options options_with_critics(const RunConfig& config) {
  Options options;
  options.hidden_sizes = config.hidden_sizes;
  options.mlp = {.zero_bias_init = config.zero_bias_init, .dtype = config.dtype, .activation = config.activation};
  options.gamma = config.gamma;
  options.actor_lr = config.first_order.actor_lr;
  options.critic_lr = config.off_policy.critic_lr;
  options.reward_scale = config.offline.reward_scale;
  options.cost_scale = config.offline.cost_scale;
  options.cost_limit = config.cost_limit;
  options.episode_length = config.max_ep_len;
  return options;
}

}  // namespace

CpqOptions cpq_options(const RunConfig& config) {
  CpqOptions options = options_with_critics<CpqOptions>(config);
  options.vae_hidden_size = config.offline.vae_hidden_size;
  options.tau = config.off_policy.polyak;
  options.vae_lr = config.offline.vae_lr;
  options.alpha_lr = config.offline.cpq_alpha_lr;
  options.vae_kl_weight = config.offline.vae_kl_weight;
  options.sampled_actions = config.offline.cpq_sampled_actions;
  options.qc_scalar = config.offline.cpq_qc_scalar;
  return options;
}

BcqLagOptions bcq_lag_options(const RunConfig& config) {
  BcqLagOptions options = options_with_critics<BcqLagOptions>(config);
  options.vae_hidden_size = config.offline.vae_hidden_size;
  options.tau = config.off_policy.polyak;
  options.vae_lr = config.offline.vae_lr;
  options.vae_kl_weight = config.offline.vae_kl_weight;
  options.phi = config.offline.bcq_phi;
  options.lambda_mix = config.offline.bcq_lambda;
  options.sampled_actions = config.offline.bcq_sampled_actions;
  options.pid_kp = config.offline.bcq_pid_kp;
  options.pid_ki = config.offline.bcq_pid_ki;
  options.pid_kd = config.offline.bcq_pid_kd;
  return options;
}

COptiDiceOptions coptidice_options(const RunConfig& config, const TrainingStatistics& statistics) {
  COptiDiceOptions options = options_with_critics<COptiDiceOptions>(config);
  options.scalar_lr = config.offline.coptidice_scalar_lr;
  options.alpha = config.offline.coptidice_alpha;
  options.cost_ub_epsilon = config.offline.coptidice_cost_ub_epsilon;
  options.f_divergence = config.offline.coptidice_f_divergence;
  options.initial_state_proportion = statistics.initial_state_proportion;
  options.action_std = statistics.action_std;
  return options;
}

TrainingRows offline_training_rows(const RunConfig& config, const OfflineDataset& dataset) {
  switch (config.alg) {
    case Algorithm::bc_all: return all_rows(dataset);
    case Algorithm::bc_safe: return rows_within_cost_limit(dataset, config.cost_limit);
    case Algorithm::cpq:
    case Algorithm::bcq_lag:
    case Algorithm::coptidice: return all_rows(dataset);
    default: not_offline(config);
  }
}

std::unique_ptr<OfflineAlgorithm> make_offline_algorithm(const RunConfig& config, int observation_size,
                                                         int action_size, const ObservationScaling& scaling,
                                                         Rng& init_rng, const TrainingStatistics& statistics) {
  const MlpOptions network{.zero_bias_init = config.zero_bias_init, .dtype = config.dtype,
                           .activation = config.activation};
  switch (config.alg) {
    case Algorithm::bc_all:
    case Algorithm::bc_safe:
      return std::make_unique<BehaviourCloning>(std::string(algorithm_info(config.alg).label), observation_size,
                                                action_size, scaling, config.hidden_sizes, network, config.first_order.actor_lr,
                                                init_rng);
    case Algorithm::cpq: return std::make_unique<Cpq>(observation_size, action_size, scaling, cpq_options(config), init_rng);
    case Algorithm::bcq_lag:
      return std::make_unique<BcqLag>(observation_size, action_size, scaling, bcq_lag_options(config), init_rng);
    case Algorithm::coptidice:
      return std::make_unique<COptiDice>(observation_size, action_size, scaling, coptidice_options(config, statistics),
                                         init_rng);
    default: not_offline(config);
  }
}

}  // namespace bsg::algos
