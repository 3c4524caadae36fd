#include "algos/first_order/p3o.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "algos/first_order/ppo.h"  // clipped_surrogate_loss

namespace bsg::algos {

SampleLossFunction p3o_cost_surrogate(const Eigen::VectorXd& cost_advantages, double clip, bool clipped) {
  return [&cost_advantages, clip, clipped](Eigen::Index sample, double ratio, double) {
    const double a = cost_advantages[sample];
    const double unclipped = ratio * a;
    if (!clipped) return SampleLoss{unclipped, a, 0.0};
    const double held = std::clamp(ratio, 1.0 - clip, 1.0 + clip) * a;
    // max(unclipped, held): the pessimistic bound of the cost; the unclipped term carries the gradient unless the clip holds rho.
    if (unclipped >= held) return SampleLoss{unclipped, a, 0.0};
    return SampleLoss{held, 0.0, 0.0};
  };
}

P3oPenalty::P3oPenalty(const PolicySurrogate& surrogate, std::vector<double> violations, double kappa, double clip,
                       bool cost_clip)
    : violations_(std::move(violations)), kappa_(kappa), clip_(clip), active_(violations_.size(), false) {
  if (static_cast<Eigen::Index>(violations_.size()) != surrogate.cost_advantages().cols()) {
    throw std::invalid_argument("P3oPenalty: " + std::to_string(violations_.size()) + " violations for " +
                                std::to_string(surrogate.cost_advantages().cols()) + " constraints");
  }
  cost_advantages_.reserve(violations_.size());  // the cost terms keep references into these vectors
  for (Eigen::Index j = 0; j < surrogate.cost_advantages().cols(); ++j) {
    cost_advantages_.emplace_back(surrogate.cost_advantages().col(j));
  }
  for (const Eigen::VectorXd& column : cost_advantages_) cost_terms_.push_back(p3o_cost_surrogate(column, clip, cost_clip));
}

double P3oPenalty::evaluate(SampleLossBatch& batch, const GaussianPolicy& policy, std::span<const Eigen::Index> rows,
                            const MpiContext& mpi) {
  std::vector<double> cost_surrogates;  // L_Cj of the rows, then averaged over ranks
  for (const SampleLossFunction& term : cost_terms_) cost_surrogates.push_back(batch.loss(policy, rows, term, nullptr));
  mpi.average_in_place(cost_surrogates.data(), cost_surrogates.size());
  double penalty = 0.0;
  for (std::size_t j = 0; j < cost_surrogates.size(); ++j) {
    const double argument = cost_surrogates[j] + violations_[j];  // L_Cj + J_Cj - d_j
    active_[j] = argument > 0.0;  // ReLU'(0) = 0, as PyTorch's
    penalty += kappa_ * std::max(argument, 0.0);
  }
  return penalty;
}

SampleLossFunction P3oPenalty::sample_loss(const Eigen::VectorXd& advantages) const {
  return [this, reward = clipped_surrogate_loss(advantages, clip_)](Eigen::Index sample, double ratio, double kl) {
    SampleLoss total = reward(sample, ratio, kl);
    for (std::size_t j = 0; j < cost_terms_.size(); ++j) {
      if (!active_[j]) continue;
      const SampleLoss cost = cost_terms_[j](sample, ratio, kl);
      total.value += kappa_ * cost.value;
      total.d_ratio += kappa_ * cost.d_ratio;
    }
    return total;
  };
}

P3o::P3o(const RunConfig& config) : FirstOrderAlgorithm(config, false, {"p3o_penalty"}) {
  if (config.alg != Algorithm::p3o) {
    throw std::invalid_argument("P3o: alg must be p3o, got " + std::string(to_string(config.alg)));
  }
  if (!std::isfinite(config.first_order.p3o_kappa) || config.first_order.p3o_kappa <= 0.0) {
    throw std::invalid_argument("p3o: p3o_kappa must be finite and > 0, got " +
                                std::to_string(config.first_order.p3o_kappa));
  }
}

PolicyUpdateResult P3o::update(const PolicyUpdateInputs& inputs) {
  check_mean_episode_cost(inputs, name());
  std::vector<double> violations;  // J_Cj - d_j
  for (const ConstraintEstimate& constraint : constraint_estimates(inputs, config())) {
    violations.push_back(constraint.mean_episode_cost - constraint.limit);
  }
  P3oPenalty penalty(inputs.surrogate, std::move(violations), config().first_order.p3o_kappa,
                     config().first_order.clip, config().first_order.p3o_cost_clip);
  double penalty_sum = 0.0;
  int steps = 0;
  const PassesFromStart update = passes_from_start(
      inputs, penalty.sample_loss(inputs.surrogate.advantages()),
      [&](SampleLossBatch& batch, std::span<const Eigen::Index> rows) {
        penalty_sum += penalty.evaluate(batch, inputs.policy, rows, inputs.mpi);
        ++steps;
      });
  // Loss/Pi: the reward loss l_R, as CUP's; the penalty has its own column.
  return make_result(common_diagnostics(inputs, update.start.before, 1.0, 0.0), update.passes,
                     {{"p3o_penalty", steps > 0 ? penalty_sum / steps : 0.0}});
}

}  // namespace bsg::algos
