#include "algos/first_order/ipo.h"

#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "algos/core/constraint_costs.h"
#include "algos/first_order/ppo.h"  // clipped_surrogate_loss
#include "algos/lagrange/lagrangian_weights.h"

namespace bsg::algos {
namespace {

// ipo_penalty, or constraint_<j>_ipo_penalty with several constraints (as the multipliers' columns).
std::vector<std::string> penalty_columns(int constraints) {
  if (constraints == 1) return {"ipo_penalty"};
  std::vector<std::string> names;
  for (int j = 1; j <= constraints; ++j) names.push_back("constraint_" + std::to_string(j) + "_ipo_penalty");
  return names;
}

void check_positive(double value, const char* key) {
  if (!std::isfinite(value) || value <= 0.0) {
    throw std::invalid_argument(std::string("ipo: ") + key + " must be finite and > 0, got " + std::to_string(value));
  }
}

}  // namespace

std::vector<double> ipo_penalties(std::span<const ConstraintEstimate> constraints, double kappa, double penalty_max) {
  std::vector<double> penalties;
  for (const ConstraintEstimate& constraint : constraints) {
    // p = kappa / (d - J_C + eps): the barrier's gradient factor; past the pole (J_C >= d) the largest penalty.
    const double penalty = kappa / (constraint.limit - constraint.mean_episode_cost + 1e-8);
    penalties.push_back(penalty < 0.0 || penalty > penalty_max ? penalty_max : penalty);
  }
  return penalties;
}

Ipo::Ipo(const RunConfig& config)
    : FirstOrderAlgorithm(config, false, penalty_columns(constraint_count(config))) {
  if (config.alg != Algorithm::ipo) {
    throw std::invalid_argument("Ipo: alg must be ipo, got " + std::string(to_string(config.alg)));
  }
  check_positive(config.first_order.ipo_kappa, "ipo_kappa");
  check_positive(config.first_order.ipo_penalty_max, "ipo_penalty_max");
}

PolicyUpdateResult Ipo::update(const PolicyUpdateInputs& inputs) {
  // 0. p_j from this epoch's J_Cj; 1. A_hat = (A - sum_j p_j A^Cj) / (1 + sum_j p_j).
  check_mean_episode_cost(inputs, name());
  const std::vector<double> penalties = ipo_penalties(constraint_estimates(inputs, config()),
                                                      config().first_order.ipo_kappa,
                                                      config().first_order.ipo_penalty_max);
  const ConstraintSurrogateWeights weights = lagrangian_surrogate_weights(penalties);
  const Eigen::VectorXd advantages = combined_advantages(inputs.surrogate, weights.reward, weights.costs);

  // 2. PPO's passes on A_hat.
  const PassesFromStart update = passes_from_start(inputs, clipped_surrogate_loss(advantages, config().first_order.clip));
  std::vector<NamedScalar> own;
  const std::vector<std::string> names = penalty_columns(static_cast<int>(penalties.size()));
  for (std::size_t j = 0; j < penalties.size(); ++j) own.push_back({names[j], penalties[j]});
  return make_result(
      common_diagnostics(inputs, update.start.before, weights.reward, std::span<const double>(weights.costs)),
      update.passes, std::move(own));
}

}  // namespace bsg::algos
