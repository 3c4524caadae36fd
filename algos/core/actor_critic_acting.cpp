#include "algos/core/actor_critic_acting.h"

namespace bsg::algos {

ActorCriticActing::ActorCriticActing(const ActorCritic& actor_critic)
    : actor_critic_(actor_critic),
      raw_(actor_critic.observation_size()),
      normalized_(actor_critic.observation_size()),
      action_(actor_critic.action_size()) {}

void ActorCriticActing::act(std::span<const double> observation, ActionMode mode, Rng& noise,
                            std::span<double> action) {
  check_acting_sizes(*this, observation, action, "policy");
  raw_ = Eigen::Map<const Eigen::VectorXd>(observation.data(), raw_.size());
  actor_critic_.normalize_observation(raw_, normalized_);
  if (mode == ActionMode::sampled) {
    actor_critic_.policy.sample_action(normalized_, action_, noise, workspace_);  // a = mu + sigma eps
  } else {
    actor_critic_.policy.mean_action(normalized_, action_, workspace_);  // a = mu_theta(s_hat)
  }
  Eigen::Map<Eigen::VectorXd>(action.data(), action_.size()) = action_;
}

}  // namespace bsg::algos
