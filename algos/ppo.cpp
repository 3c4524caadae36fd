#include "algos/ppo.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "algos/lag_trpo.h"

namespace bsg {

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

std::vector<NamedScalar> first_order_state(const LagrangeMultipliers* multipliers, const PolicyAdam& adam) {
  std::vector<NamedScalar> state = multipliers ? multipliers->state() : std::vector<NamedScalar>{};
  for (NamedScalar& entry : adam.state()) state.push_back(std::move(entry));
  return state;
}

void restore_first_order_state(std::span<const NamedScalar> saved, LagrangeMultipliers* multipliers, PolicyAdam& adam) {
  const std::size_t adam_entries = PolicyAdam::saved_size(saved);
  const std::span<const NamedScalar> multiplier_state = saved.first(saved.size() - adam_entries);
  if (multipliers != nullptr) {
    multipliers->restore_state(multiplier_state);
  } else if (!multiplier_state.empty()) {
    throw std::invalid_argument("unexpected state entry '" + multiplier_state.front().name + "'");
  }
  adam.restore_state(saved.last(adam_entries));
}

Ppo::Ppo(const RunConfig& config)
    : TrustRegionAlgorithm(config),
      lagrangian_(config.alg == Algorithm::ppo_lag),
      multipliers_(config),
      adam_(config.actor_lr) {
  if (config.alg != Algorithm::ppo && config.alg != Algorithm::ppo_lag) {
    throw std::invalid_argument("Ppo: alg must be ppo or ppo-lag, got " + std::string(to_string(config.alg)));
  }
}

std::vector<std::string> Ppo::diagnostic_names() const {
  std::vector<std::string> names = common_diagnostic_names();
  for (std::string& name : first_order_diagnostic_names()) names.push_back(std::move(name));
  if (lagrangian_) {
    for (std::string& name : multipliers_.diagnostic_names()) names.push_back(std::move(name));
  }
  return names;
}

std::vector<NamedScalar> Ppo::state() const { return first_order_state(multipliers(), adam_); }

void Ppo::restore_state(std::span<const NamedScalar> saved) {
  restore_first_order_state(saved, lagrangian_ ? &multipliers_ : nullptr, adam_);
}

PolicyUpdateResult Ppo::update(const PolicyUpdateInputs& inputs) {
  // 0. PPO-Lag: lambda_j first, then A_hat = (A - sum_j lambda_j A^Cj) / (1 + sum_j lambda_j).
  ConstraintSurrogateWeights weights;
  weights.costs.assign(static_cast<std::size_t>(inputs.surrogate.constraint_count()), 0.0);
  if (lagrangian_) {
    check_mean_episode_cost(inputs, name());
    weights = lagrangian_surrogate_weights(multipliers_.update(constraint_estimates(inputs, config())));
  }
  const Eigen::VectorXd advantages = combined_advantages(inputs.surrogate, weights.reward, weights.costs);

  const PolicyUpdateStart start = begin_policy_update(inputs);
  SampleLossBatch batch(inputs.surrogate, inputs.surrogate.reference_means());
  // 1. The clipped surrogate's minibatch passes.
  const MinibatchPassesResult passes = minibatch_passes(inputs, first_order_options(config()), adam_, batch,
                                                        clipped_surrogate_loss(advantages, config().clip));

  PolicyUpdateResult result;
  result.diagnostics = common_diagnostics(inputs, start.before, weights.reward, std::span<const double>(weights.costs));
  append_first_order_diagnostics(result.diagnostics, passes);
  if (lagrangian_) {
    for (NamedScalar& entry : multipliers_.diagnostics()) result.diagnostics.push_back(std::move(entry));
  }
  return result;
}

}  // namespace bsg
