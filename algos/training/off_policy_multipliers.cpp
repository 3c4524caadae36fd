#include "algos/training/off_policy_multipliers.h"

#include <numeric>

#include "algos/core/constraint_costs.h"

namespace bsg::algos {

OffPolicyMultipliers::OffPolicyMultipliers(const RunConfig& config)
    : multipliers_(config),
      schedule_(config.off_policy.multiplier_schedule),
      window_(static_cast<std::size_t>(config.off_policy.multiplier_window)),
      recent_costs_(static_cast<std::size_t>(multipliers_.count())),
      pooled_(static_cast<std::size_t>(multipliers_.count()) + 1, 0.0),
      estimates_(static_cast<std::size_t>(multipliers_.count())) {
  for (int i = 0; i < multipliers_.count(); ++i) limits_.push_back(constraint_limit(config, i));
}

void OffPolicyMultipliers::restart() {
  for (std::deque<double>& costs : recent_costs_) costs.clear();
}

void OffPolicyMultipliers::record(const std::vector<std::vector<double>>& constraint_costs, std::size_t first) {
  for (std::size_t i = 0; i < recent_costs_.size(); ++i) {
    const std::vector<double>& costs = constraint_costs.at(i);
    for (std::size_t e = first; e < costs.size(); ++e) {
      recent_costs_[i].push_back(costs[e]);
      if (recent_costs_[i].size() > window_) recent_costs_[i].pop_front();
    }
  }
}

bool OffPolicyMultipliers::before_gradient_round(bool learning, const MpiContext& mpi) {
  if (schedule_ != MultiplierSchedule::update_round || !learning) return false;
  // Every constraint's window holds the same episodes: one count, after the sums.
  for (std::size_t i = 0; i < recent_costs_.size(); ++i) {
    pooled_[i] = std::accumulate(recent_costs_[i].begin(), recent_costs_[i].end(), 0.0);
  }
  pooled_.back() = recent_costs_.empty() ? 0.0 : static_cast<double>(recent_costs_.front().size());
  mpi.sum_in_place(pooled_.data(), pooled_.size());
  const double count = pooled_.back();
  if (count <= 0.0) return false;
  for (std::size_t i = 0; i < estimates_.size(); ++i) estimates_[i] = {pooled_[i] / count, limits_[i]};
  multipliers_.update(estimates_);
  return true;
}

bool OffPolicyMultipliers::after_epoch(std::span<const ConstraintEstimate> constraints, long long episode_count) {
  if (schedule_ != MultiplierSchedule::epoch || episode_count <= 0) return false;
  multipliers_.update(constraints);
  return true;
}

}  // namespace bsg::algos
