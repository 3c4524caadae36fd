#include "algos/off_policy/sac_learner.h"

#include <algorithm>
#include <cmath>

namespace bsg::algos {

SacLearner::SacLearner(OffPolicyOptions options, int observation_size, int action_size, int cost_count,
                       Rng& init_rng)
    : OffPolicyLearner(std::move(options), observation_size, action_size, cost_count, 2 * action_size,
                       /*reward_critics=*/2, init_rng),
      temperature_(this->options().alpha_init, this->options().alpha_lr, this->options().target_entropy) {}

void SacLearner::action_from_outputs(const Eigen::VectorXd& outputs, bool deterministic, Rng& rng,
                                     Eigen::Ref<Eigen::VectorXd> action) const {
  const Eigen::Index action_size = action.size();
  for (Eigen::Index j = 0; j < action_size; ++j) {
    double u = outputs(j);
    if (!deterministic) {
      const double log_std = std::clamp(outputs(action_size + j), kLogStdMin, kLogStdMax);
      u += std::exp(log_std) * standard_normal(rng);  // u = mu + sigma eps
    }
    action(j) = std::tanh(u);
  }
}

void SacLearner::next_actions(const Eigen::MatrixXd& next_observations,
                              const Eigen::Ref<const Eigen::MatrixXd>& next_noise, Eigen::MatrixXd& actions) {
  const Eigen::MatrixXd& outputs = actor().forward_batch(next_observations, actor_workspace());
  squashed_gaussian_sample(outputs, next_noise, sample_);
  actions = sample_.actions;
}

void SacLearner::add_next_value_terms(Eigen::MatrixXd& next_values) const {
  next_values.col(0) -= temperature_.alpha() * sample_.log_probs;  // soft value
}

void SacLearner::policy_actions(const Eigen::MatrixXd& outputs, const Eigen::Ref<const Eigen::MatrixXd>& noise,
                                Eigen::MatrixXd& actions) {
  squashed_gaussian_sample(outputs, noise, sample_);
  actions = sample_.actions;
}

void SacLearner::actor_output_gradient(const Eigen::MatrixXd& outputs, const Eigen::Ref<const Eigen::MatrixXd>& noise,
                                       const Eigen::MatrixXd& /*actions*/, const Eigen::MatrixXd& action_gradient,
                                       double scale, double& loss_sum, double* log_prob_mean,
                                       Eigen::MatrixXd& output_gradient) {
  // + alpha log pi(a|s)
  const double alpha_value = temperature_.alpha();
  loss_sum += alpha_value * sample_.log_probs.sum();
  if (log_prob_mean != nullptr) *log_prob_mean = sample_.log_probs.mean();
  if (log_prob_gradient_.size() != outputs.rows()) log_prob_gradient_.resize(outputs.rows());
  log_prob_gradient_.setConstant(alpha_value * scale);
  squashed_gaussian_backward(outputs, noise, sample_, action_gradient, log_prob_gradient_, output_gradient);
}

void SacLearner::after_actor_step(double log_prob_mean, const MpiContext& mpi) {
  if (options().auto_alpha) temperature_.step(mpi.average(log_prob_mean));
}

}  // namespace bsg::algos
