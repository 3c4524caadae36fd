#include "algos/off_policy/td3_learner.h"

#include "algos/off_policy/target_smoothing.h"

namespace bsg::algos {

Td3Learner::Td3Learner(OffPolicyOptions options, int observation_size, int action_size, int cost_count,
                       Rng& init_rng)
    : DeterministicActorLearner(std::move(options), observation_size, action_size, cost_count, /*reward_critics=*/2,
                                init_rng) {}

void Td3Learner::next_actions(const Eigen::MatrixXd& next_observations,
                              const Eigen::Ref<const Eigen::MatrixXd>& next_noise, Eigen::MatrixXd& actions) {
  target_actor_actions(next_observations, actions);
  smooth_target_actions(actions, next_noise, options().policy_noise, options().noise_clip);
}

}  // namespace bsg::algos
