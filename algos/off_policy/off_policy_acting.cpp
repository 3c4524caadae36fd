#include "algos/off_policy/off_policy_acting.h"

namespace bsg::algos {

OffPolicyActing::OffPolicyActing(OffPolicyLearner& learner) : learner_(learner), action_(learner.action_size()) {}

void OffPolicyActing::act(std::span<const double> observation, ActionMode mode, Rng& noise, std::span<double> action) {
  check_acting_sizes(*this, observation, action, "policy");
  learner_.act(observation, mode == ActionMode::mean, noise, action_);
  Eigen::Map<Eigen::VectorXd>(action.data(), action_.size()) = action_;
}

}  // namespace bsg::algos
