#include "algos/first_order/ppo.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "algos/lagrange/lagrangian_weights.h"

namespace bsg::algos {

SampleLossFunction clipped_surrogate_loss(const Eigen::VectorXd& advantages, double clip) {
  return [&advantages, clip](Eigen::Index sample, double ratio, double) {
    const double a = advantages[sample];
    const double unclipped = ratio * a;
    const double clipped = std::clamp(ratio, 1.0 - clip, 1.0 + clip) * a;
    // min(unclipped, clipped): the unclipped term carries the gradient unless the clip holds rho.
    if (unclipped <= clipped) return SampleLoss{-unclipped, -a, 0.0};
    return SampleLoss{-clipped, 0.0, 0.0};
  };
}

Ppo::Ppo(const RunConfig& config) : FirstOrderAlgorithm(config, config.alg == Algorithm::ppo_lag, {}) {
  // PPOSaute, PPOEarlyTerminated and PPOSimmerPID take PPO's update; their budget decorator changes the data.
  if (config.alg != Algorithm::ppo && config.alg != Algorithm::ppo_lag && config.alg != Algorithm::ppo_saute &&
      config.alg != Algorithm::ppo_early_terminated && config.alg != Algorithm::ppo_simmer) {
    throw std::invalid_argument("Ppo: alg must be ppo, ppo-lag, ppo-saute, ppo-early-terminated or ppo-simmer, got " +
                                std::string(to_string(config.alg)));
  }
}

PolicyUpdateResult Ppo::update(const PolicyUpdateInputs& inputs) {
  // 0. PPO-Lag: lambda_j first, then A_hat = (A - sum_j lambda_j A^Cj) / (1 + sum_j lambda_j).
  ConstraintSurrogateWeights weights;
  weights.costs.assign(static_cast<std::size_t>(inputs.surrogate.constraint_count()), 0.0);
  if (multipliers() != nullptr) weights = lagrangian_surrogate_weights(update_multipliers(inputs));
  const Eigen::VectorXd advantages = combined_advantages(inputs.surrogate, weights.reward, weights.costs);

  // 1. The clipped surrogate's minibatch passes.
  const PassesFromStart update = passes_from_start(inputs, clipped_surrogate_loss(advantages, config().first_order.clip));
  return make_result(
      common_diagnostics(inputs, update.start.before, weights.reward, std::span<const double>(weights.costs)),
      update.passes, {});
}

}  // namespace bsg::algos
