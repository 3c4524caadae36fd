#include "algos/first_order/focops.h"

#include <vector>

namespace bsg::algos {

SampleLossFunction focops_loss(const Eigen::VectorXd& advantages, double temperature, double kl_bound) {
  return [&advantages, temperature, kl_bound](Eigen::Index sample, double ratio, double kl) {
    if (kl > kl_bound) return SampleLoss{};  // masked: 1[KL_i <= eta] = 0
    return SampleLoss{kl - ratio * advantages[sample] / temperature, -advantages[sample] / temperature, 1.0};
  };
}

Focops::Focops(const RunConfig& config) : FirstOrderAlgorithm(config, true, {}) {}

PolicyUpdateResult Focops::update(const PolicyUpdateInputs& inputs) {
  // 0. nu_j first, then A_hat = A - sum_j nu_j A^Cj.
  std::vector<double> cost_weights;
  for (double nu : update_multipliers(inputs)) cost_weights.push_back(-nu);
  const Eigen::VectorXd advantages = combined_advantages(inputs.surrogate, 1.0, cost_weights);

  // 1. The masked loss's minibatch passes, KL_i to pi_theta_k.
  const PassesFromStart update = passes_from_start(
      inputs, focops_loss(advantages, config().first_order.focops_lam, config().first_order.focops_eta));
  return make_result(common_diagnostics(inputs, update.start.before, 1.0, std::span<const double>(cost_weights)),
                     update.passes, {});
}

}  // namespace bsg::algos
