// The on-policy families' acting policy (acting_policy.h): the observation normalised with the
// actor-critic's statistics, then the Gaussian policy's mean action mu_theta(s_hat) or a sample
// mu + sigma eps at its current sigma.
#pragma once

#include <Eigen/Core>

#include "algos/core/acting_policy.h"
#include "algos/core/actor_critic.h"

namespace bsg::algos {

class ActorCriticActing final : public ActingPolicy {
 public:
  explicit ActorCriticActing(const ActorCritic& actor_critic);

  int observation_size() const override { return actor_critic_.observation_size(); }
  int action_size() const override { return actor_critic_.action_size(); }
  void act(std::span<const double> observation, ActionMode mode, Rng& noise, std::span<double> action) override;

 private:
  const ActorCritic& actor_critic_;
  Eigen::VectorXd raw_;
  Eigen::VectorXd normalized_;
  Eigen::VectorXd action_;
  MlpSampleWorkspace workspace_;
};

}  // namespace bsg::algos
