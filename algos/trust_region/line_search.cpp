#include "algos/trust_region/line_search.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace bsg::algos {
namespace {

void check_options(const LineSearchOptions& options, const char* where) {
  if (options.budget <= 0) {
    throw std::invalid_argument(std::string(where) + ": budget must be positive, got " +
                                std::to_string(options.budget));
  }
  if (!(options.decay > 0.0 && options.decay < 1.0)) {
    throw std::invalid_argument(std::string(where) + ": decay must lie in (0, 1), got " +
                                std::to_string(options.decay));
  }
  if (!(options.target_kl > 0.0)) {
    throw std::invalid_argument(std::string(where) + ": target_kl must be positive, got " +
                                std::to_string(options.target_kl));
  }
  if (!(options.kl_accept_factor > 0.0)) {
    throw std::invalid_argument(std::string(where) + ": kl_accept_factor must be positive, got " +
                                std::to_string(options.kl_accept_factor));
  }
}

}  // namespace

LineSearchResult trpo_line_search(const Eigen::Ref<const Eigen::VectorXd>& full_step, double loss_old,
                                  const LossEvaluator& evaluate, const MpiContext& mpi,
                                  const LineSearchOptions& options) {
  check_options(options, "trpo_line_search");
  if (!evaluate) throw std::invalid_argument("trpo_line_search: evaluate is empty");
  LineSearchResult result;
  result.step = Eigen::VectorXd::Zero(full_step.size());
  Eigen::VectorXd trial_step(full_step.size());
  for (int j = 0; j < options.budget; ++j) {
    trial_step = std::pow(options.decay, j) * full_step;  // 0.8^j Delta
    const LossAndKl trial = evaluate(trial_step);
    // One allreduce: [l_old - l_j, KL_j, non-finite flag].
    double reduced[3] = {loss_old - trial.loss, trial.kl,
                         std::isfinite(trial.loss) && std::isfinite(trial.kl) ? 0.0 : 1.0};
    mpi.average_in_place(reduced, 3);
    const double improvement = reduced[0];  // I_j
    const double kl = reduced[1];           // K_j
    if (reduced[2] != 0.0 || !std::isfinite(improvement) || !std::isfinite(kl)) continue;
    if (improvement < 0.0) continue;
    if (kl > options.kl_accept_factor * options.target_kl) continue;
    result.step = trial_step;
    result.acceptance_step = j + 1;
    result.improvement = improvement;
    result.kl = kl;
    break;
  }
  return result;
}

LineSearchResult constrained_line_search(const Eigen::Ref<const Eigen::VectorXd>& full_step,
                                         const ConstrainedLineSearchInputs& inputs,
                                         const ConstrainedEvaluator& evaluate, const MpiContext& mpi,
                                         const LineSearchOptions& options) {
  check_options(options, "constrained_line_search");
  if (!evaluate) throw std::invalid_argument("constrained_line_search: evaluate is empty");
  LineSearchResult result;
  result.step = Eigen::VectorXd::Zero(full_step.size());
  Eigen::VectorXd trial_step(full_step.size());
  const double allowed_cost_change = std::max(-inputs.constraint_violation, 0.0);  // max(-c, 0)
  for (int j = 0; j < options.budget; ++j) {
    trial_step = std::pow(options.decay, j) * full_step;
    const ConstrainedTrial trial = evaluate(trial_step);
    const bool finite =
        std::isfinite(trial.reward_loss) && std::isfinite(trial.cost_surrogate) && std::isfinite(trial.kl);
    // One allreduce: [I_j, D_j, K_j, non-finite flag].
    double reduced[4] = {inputs.reward_loss_old - trial.reward_loss, trial.cost_surrogate - inputs.cost_surrogate_old,
                         trial.kl, finite ? 0.0 : 1.0};
    mpi.average_in_place(reduced, 4);
    const double improvement = reduced[0];  // I_j
    const double cost_change = reduced[1];  // D_j
    const double kl = reduced[2];           // K_j
    if (reduced[3] != 0.0) continue;
    if (inputs.require_reward_improvement && improvement < 0.0) continue;
    if (cost_change > allowed_cost_change) continue;
    if (kl > options.kl_accept_factor * options.target_kl) continue;
    result.step = trial_step;
    result.acceptance_step = j + 1;
    result.improvement = improvement;
    result.cost_change = cost_change;
    result.kl = kl;
    break;
  }
  return result;
}

}  // namespace bsg::algos
