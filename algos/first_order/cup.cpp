#include "algos/first_order/cup.h"

#include <vector>

#include "algos/first_order/ppo.h"  // clipped_surrogate_loss

namespace bsg::algos {

SampleLossFunction cup_projection_loss(const Eigen::VectorXd& weighted_cost_advantages) {
  return [&weighted_cost_advantages](Eigen::Index sample, double ratio, double kl) {
    const double a = weighted_cost_advantages[sample];
    return SampleLoss{kl + ratio * a, a, 1.0};
  };
}

Cup::Cup(const RunConfig& config) : FirstOrderAlgorithm(config, true, {"Misc/SecondStepStopIter"}) {}

PolicyUpdateResult Cup::update(const PolicyUpdateInputs& inputs) {
  // 0. nu_j first.
  const std::vector<double> nu = update_multipliers(inputs);
  const FirstOrderOptions options = first_order_options(config());

  // 1. Performance step: PPO on the reward advantage, KL to pi_k.
  const PassesFromStart performance =
      passes_from_start(inputs, clipped_surrogate_loss(inputs.surrogate.advantages(), config().first_order.clip));

  // 2. Projection step from pi_{k+1/2}: l_i = KL_i + c rho_i sum_j nu_j A^Cj_i.
  const double c = (1.0 - config().gamma * config().lam_c) / (1.0 - config().gamma);
  std::vector<double> cost_weights;
  for (double nu_j : nu) cost_weights.push_back(c * nu_j);
  const Eigen::VectorXd weighted_cost_advantages = combined_advantages(inputs.surrogate, 0.0, cost_weights);
  const Eigen::MatrixXd half_step_means = policy_means(inputs.policy, inputs.surrogate.observations());
  SampleLossBatch projection_batch(inputs.surrogate, half_step_means, inputs.policy.log_stds());
  const MinibatchPassesResult projection =
      minibatch_passes(inputs, options, adam(), projection_batch, cup_projection_loss(weighted_cost_advantages));

  // Loss/Pi: the reward loss l_R.
  return make_result(common_diagnostics(inputs, performance.start.before, 1.0, 0.0), performance.passes,
                     {{"Misc/SecondStepStopIter", static_cast<double>(projection.passes)}});
}

}  // namespace bsg::algos
