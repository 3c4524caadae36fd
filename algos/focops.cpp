#include "algos/focops.h"

#include <stdexcept>
#include <string>

#include "algos/ppo.h"

namespace bsg {

SampleLossFunction focops_loss(const Eigen::VectorXd& advantages, double temperature, double kl_bound) {
  return [&advantages, temperature, kl_bound](Eigen::Index sample, double ratio, double kl) {
    if (kl > kl_bound) return SampleLoss{};  // masked: 1[KL_i <= eta] = 0
    return SampleLoss{kl - ratio * advantages[sample] / temperature, -advantages[sample] / temperature, 1.0};
  };
}

Focops::Focops(const RunConfig& config) : TrustRegionAlgorithm(config), multipliers_(config), adam_(config.actor_lr) {}

std::vector<std::string> Focops::diagnostic_names() const {
  std::vector<std::string> names = common_diagnostic_names();
  for (std::string& name : first_order_diagnostic_names()) names.push_back(std::move(name));
  for (std::string& name : multipliers_.diagnostic_names()) names.push_back(std::move(name));
  return names;
}

std::vector<NamedScalar> Focops::state() const { return first_order_state(&multipliers_, adam_); }

void Focops::restore_state(std::span<const NamedScalar> saved) { restore_first_order_state(saved, &multipliers_, adam_); }

PolicyUpdateResult Focops::update(const PolicyUpdateInputs& inputs) {
  check_mean_episode_cost(inputs, name());
  // 0. nu_j first, then A_hat = A - sum_j nu_j A^Cj.
  const std::vector<double> nu = multipliers_.update(constraint_estimates(inputs, config()));
  std::vector<double> cost_weights;
  for (double nu_j : nu) cost_weights.push_back(-nu_j);
  const Eigen::VectorXd advantages = combined_advantages(inputs.surrogate, 1.0, cost_weights);

  const PolicyUpdateStart start = begin_policy_update(inputs);
  SampleLossBatch batch(inputs.surrogate, inputs.surrogate.reference_means());  // KL_i to pi_theta_k
  // 1. The masked loss's minibatch passes.
  const MinibatchPassesResult passes =
      minibatch_passes(inputs, first_order_options(config()), adam_, batch,
                       focops_loss(advantages, config().focops_lam, config().focops_eta));

  PolicyUpdateResult result;
  result.diagnostics = common_diagnostics(inputs, start.before, 1.0, std::span<const double>(cost_weights));
  append_first_order_diagnostics(result.diagnostics, passes);
  for (NamedScalar& entry : multipliers_.diagnostics()) result.diagnostics.push_back(std::move(entry));
  return result;
}

}  // namespace bsg
