// The off-policy learners' acting policy (acting_policy.h): observations enter unnormalised, as
// the learner trained on them; deterministic actions are the actor's tanh(mu(s)), sampled ones its
// exploring actions (SAC's squashed sample; TD3's and DDPG's Gaussian noise).
#pragma once

#include <Eigen/Core>

#include "algos/core/acting_policy.h"
#include "algos/off_policy/off_policy_learner.h"

namespace bsg::algos {

class OffPolicyActing final : public ActingPolicy {
 public:
  explicit OffPolicyActing(OffPolicyLearner& learner);

  int observation_size() const override { return learner_.observation_size(); }
  int action_size() const override { return learner_.action_size(); }
  void act(std::span<const double> observation, ActionMode mode, Rng& noise, std::span<double> action) override;

 private:
  OffPolicyLearner& learner_;
  Eigen::VectorXd action_;
};

}  // namespace bsg::algos
