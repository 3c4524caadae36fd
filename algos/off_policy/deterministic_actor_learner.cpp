#include "algos/off_policy/deterministic_actor_learner.h"

#include <algorithm>
#include <cmath>

namespace bsg::algos {

DeterministicActorLearner::DeterministicActorLearner(OffPolicyOptions options, int observation_size, int action_size,
                                                     int cost_count, int reward_critics, Rng& init_rng)
    : OffPolicyLearner(std::move(options), observation_size, action_size, cost_count, action_size, reward_critics,
                       init_rng) {}

void DeterministicActorLearner::target_actor_actions(const Eigen::MatrixXd& next_observations,
                                                     Eigen::MatrixXd& actions) {
  actions = target_actor().forward_batch(next_observations, actor_workspace()).array().tanh();
}

void DeterministicActorLearner::action_from_outputs(const Eigen::VectorXd& outputs, bool deterministic, Rng& rng,
                                                    Eigen::Ref<Eigen::VectorXd> action) const {
  for (Eigen::Index j = 0; j < action.size(); ++j) {
    double a = std::tanh(outputs(j));
    if (!deterministic) a = std::clamp(a + options().exploration_noise * standard_normal(rng), -1.0, 1.0);
    action(j) = a;
  }
}

void DeterministicActorLearner::policy_actions(const Eigen::MatrixXd& outputs,
                                               const Eigen::Ref<const Eigen::MatrixXd>& /*noise*/,
                                               Eigen::MatrixXd& actions) {
  actions = outputs.array().tanh();
}

void DeterministicActorLearner::actor_output_gradient(const Eigen::MatrixXd& /*outputs*/,
                                                      const Eigen::Ref<const Eigen::MatrixXd>& /*noise*/,
                                                      const Eigen::MatrixXd& actions,
                                                      const Eigen::MatrixXd& action_gradient, double /*scale*/,
                                                      double& /*loss_sum*/, double* log_prob_mean,
                                                      Eigen::MatrixXd& output_gradient) {
  if (log_prob_mean != nullptr) *log_prob_mean = 0.0;
  // a = tanh(o): dL/do = dL/da (1 - a^2)
  output_gradient = action_gradient.array() * (1.0 - actions.array().square());
}

}  // namespace bsg::algos
