#include "algos/off_policy/ddpg_learner.h"

namespace bsg::algos {

DdpgLearner::DdpgLearner(OffPolicyOptions options, int observation_size, int action_size, int cost_count,
                         Rng& init_rng)
    : DeterministicActorLearner(std::move(options), observation_size, action_size, cost_count, /*reward_critics=*/1,
                                init_rng) {}

void DdpgLearner::next_actions(const Eigen::MatrixXd& next_observations,
                               const Eigen::Ref<const Eigen::MatrixXd>& /*next_noise*/, Eigen::MatrixXd& actions) {
  target_actor_actions(next_observations, actions);
}

}  // namespace bsg::algos
