// What TD3 (td3_learner.h) and DDPG (ddpg_learner.h) share over the off-policy base: the
// deterministic actor a = tanh(mu(s)) (Silver et al. 2014; Lillicrap et al. 2016) with its target
// copy mu', exploring with clip(tanh(mu(s)) + N(0, exploration_noise^2), -1, 1), and the actor's
// loss -Q_1(s, tanh(mu(s))) (Fujimoto et al.'s actor uses Q_1 alone; + the base's Lagrangian
// terms) whose gradient reaches mu through dQ/da and the tanh: dL/dmu = dL/da (1 - a^2).
// Each learner gives its critic target's a' (next_actions) and whether it draws noise for it.
#pragma once

#include "algos/off_policy/off_policy_learner.h"

namespace bsg::algos {

class DeterministicActorLearner : public OffPolicyLearner {
 public:
  ActorKind actor_kind() const override { return ActorKind::deterministic; }

 protected:
  DeterministicActorLearner(OffPolicyOptions options, int observation_size, int action_size, int cost_count,
                            int reward_critics, Rng& init_rng);

  // mu'(s') squashed: tanh of the target actor's outputs (N x |A|).
  void target_actor_actions(const Eigen::MatrixXd& next_observations, Eigen::MatrixXd& actions);

  void action_from_outputs(const Eigen::VectorXd& outputs, bool deterministic, Rng& rng,
                           Eigen::Ref<Eigen::VectorXd> action) const override;
  bool draws_actor_noise() const override { return false; }
  void policy_actions(const Eigen::MatrixXd& outputs, const Eigen::Ref<const Eigen::MatrixXd>& noise,
                      Eigen::MatrixXd& actions) override;
  int critics_in_actor_loss() const override { return 1; }
  void actor_output_gradient(const Eigen::MatrixXd& outputs, const Eigen::Ref<const Eigen::MatrixXd>& noise,
                             const Eigen::MatrixXd& actions, const Eigen::MatrixXd& action_gradient, double scale,
                             double& loss_sum, double* log_prob_mean, Eigen::MatrixXd& output_gradient) override;
  bool uses_target_actor() const override { return true; }
};

}  // namespace bsg::algos
