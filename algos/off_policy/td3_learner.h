// TD3 (Fujimoto et al. 2018; alg: td3, td3-lag): the deterministic actor (deterministic_actor_learner.h),
// twin reward critics whose minimum gives the target (clipped double Q), target policy smoothing
//   y = R + discount (1 - terminal) min_k Q'_k(s', a'),  a' = clip(mu'(s') + clip(eps, -c, c), -1, 1)
// with eps ~ N(0, policy_noise^2), c = noise_clip (target_smoothing.h, eq. 14), and the actor and
// every target updated once per policy_delay critic steps (the base's schedule).
//
// Parameters (configs/algorithms/td3.yaml, OmniSafe's): policy_noise 0.2, noise_clip 0.5, policy_delay 2.
#pragma once

#include "algos/off_policy/deterministic_actor_learner.h"

namespace bsg::algos {

class Td3Learner final : public DeterministicActorLearner {
 public:
  Td3Learner(OffPolicyOptions options, int observation_size, int action_size, int cost_count, Rng& init_rng);

 protected:
  bool draws_target_noise() const override { return true; }
  void next_actions(const Eigen::MatrixXd& next_observations, const Eigen::Ref<const Eigen::MatrixXd>& next_noise,
                    Eigen::MatrixXd& actions) override;
};

}  // namespace bsg::algos
