// SAC (Haarnoja et al. 2018; alg: sac, sac-lag, Ha et al. 2020 for the latter): the tanh-squashed
// Gaussian actor (squashed_gaussian.h: the actor net gives mu and log sigma, 2|A| outputs), twin
// reward critics and the entropy temperature alpha (temperature.h):
//   critic target  y = R + discount (1 - terminal) (min_k Q'_k(s', a') - alpha log pi(a'|s')),
//                  a' ~ pi(.|s') from the online actor (no target actor)
//   actor target   a = tanh(mu + sigma eps) reparameterised; L_pi adds alpha log pi(a|s) to the
//                  base's -min_k Q_k(s, a) + sum_i lambda_i Q_Ci(s, a), through both twins
//   temperature    with auto_alpha, one Adam step on log alpha after each actor step, on the
//                  rank-averaged mean log pi
// Exploring actions are tanh(mu + sigma eps), evaluation's tanh(mu).
#pragma once

#include "algos/off_policy/off_policy_learner.h"
#include "algos/core/squashed_gaussian.h"
#include "algos/off_policy/temperature.h"

namespace bsg::algos {

class SacLearner final : public OffPolicyLearner {
 public:
  SacLearner(OffPolicyOptions options, int observation_size, int action_size, int cost_count, Rng& init_rng);

  ActorKind actor_kind() const override { return ActorKind::squashed_gaussian; }
  const Temperature* temperature() const override { return &temperature_; }

 protected:
  void action_from_outputs(const Eigen::VectorXd& outputs, bool deterministic, Rng& rng,
                           Eigen::Ref<Eigen::VectorXd> action) const override;
  bool draws_target_noise() const override { return true; }
  bool draws_actor_noise() const override { return true; }
  void next_actions(const Eigen::MatrixXd& next_observations, const Eigen::Ref<const Eigen::MatrixXd>& next_noise,
                    Eigen::MatrixXd& actions) override;
  void add_next_value_terms(Eigen::MatrixXd& next_values) const override;
  void policy_actions(const Eigen::MatrixXd& outputs, const Eigen::Ref<const Eigen::MatrixXd>& noise,
                      Eigen::MatrixXd& actions) override;
  int critics_in_actor_loss() const override { return reward_critic_count(); }
  void actor_output_gradient(const Eigen::MatrixXd& outputs, const Eigen::Ref<const Eigen::MatrixXd>& noise,
                             const Eigen::MatrixXd& actions, const Eigen::MatrixXd& action_gradient, double scale,
                             double& loss_sum, double* log_prob_mean, Eigen::MatrixXd& output_gradient) override;
  void after_actor_step(double log_prob_mean, const MpiContext& mpi) override;
  bool uses_target_actor() const override { return false; }
  Temperature* mutable_temperature() override { return &temperature_; }

 private:
  Temperature temperature_;
  SquashedGaussianSample sample_;      // of the last next_actions or policy_actions
  Eigen::VectorXd log_prob_gradient_;  // N: dL/dlog pi
};

}  // namespace bsg::algos
