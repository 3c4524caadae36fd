// DDPG (Lillicrap et al. 2016; alg: ddpg, ddpg-lag): the deterministic actor
// (deterministic_actor_learner.h) and one reward critic, bootstrapped from the target nets:
//   y = R + discount (1 - terminal) Q'(s', mu'(s'))
// A step draws no random numbers (no smoothing, no sampled actor).
#pragma once

#include "algos/off_policy/deterministic_actor_learner.h"

namespace bsg::algos {

class DdpgLearner final : public DeterministicActorLearner {
 public:
  DdpgLearner(OffPolicyOptions options, int observation_size, int action_size, int cost_count, Rng& init_rng);

 protected:
  bool draws_target_noise() const override { return false; }
  void next_actions(const Eigen::MatrixXd& next_observations, const Eigen::Ref<const Eigen::MatrixXd>& next_noise,
                    Eigen::MatrixXd& actions) override;
};

}  // namespace bsg::algos
