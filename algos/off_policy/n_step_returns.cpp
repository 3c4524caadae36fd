#include "algos/off_policy/n_step_returns.h"

#include <stdexcept>
#include <string>

namespace bsg::algos {

NStepAccumulator::NStepAccumulator(int n, double gamma, int observation_size, int action_size, int cost_count)
    : n_(n), gamma_(gamma) {
  if (n < 1) throw std::invalid_argument("NStepAccumulator: n = " + std::to_string(n) + " must be at least 1");
  if (!(gamma > 0.0 && gamma <= 1.0)) {
    throw std::invalid_argument("NStepAccumulator: gamma = " + std::to_string(gamma) + " outside (0, 1]");
  }
  const std::size_t slots = static_cast<std::size_t>(n);
  observations_.assign(slots, Eigen::VectorXd(observation_size));
  actions_.assign(slots, Eigen::VectorXd(action_size));
  costs_.assign(slots, Eigen::VectorXd(cost_count));
  rewards_.assign(slots, 0.0);
  cost_sum_.resize(cost_count);
}

void NStepAccumulator::emit_oldest(std::span<const double> next_observation, bool terminal, ReplayBuffer& buffer) {
  // R = sum_{k < count} gamma^k r_{t+k}, the same for each cost; discount gamma^count.
  double reward_sum = 0.0;
  cost_sum_.setZero();
  double discount = 1.0;
  for (int k = 0; k < count_; ++k) {
    const std::size_t slot = static_cast<std::size_t>((first_ + k) % n_);
    reward_sum += discount * rewards_[slot];
    cost_sum_ += discount * costs_[slot];
    discount *= gamma_;
  }
  const std::size_t oldest = static_cast<std::size_t>(first_);
  buffer.add(std::span<const double>(observations_[oldest].data(), static_cast<std::size_t>(observations_[oldest].size())),
             std::span<const double>(actions_[oldest].data(), static_cast<std::size_t>(actions_[oldest].size())),
             reward_sum, std::span<const double>(cost_sum_.data(), static_cast<std::size_t>(cost_sum_.size())),
             next_observation, discount, terminal);
  first_ = (first_ + 1) % n_;
  --count_;
}

void NStepAccumulator::add(std::span<const double> observation, std::span<const double> action, double reward,
                           std::span<const double> costs, std::span<const double> next_observation, bool terminated,
                           bool episode_ends, ReplayBuffer& buffer) {
  const std::size_t slot = static_cast<std::size_t>((first_ + count_) % n_);
  observations_[slot] = Eigen::Map<const Eigen::VectorXd>(observation.data(), static_cast<Eigen::Index>(observation.size()));
  actions_[slot] = Eigen::Map<const Eigen::VectorXd>(action.data(), static_cast<Eigen::Index>(action.size()));
  costs_[slot] = Eigen::Map<const Eigen::VectorXd>(costs.data(), static_cast<Eigen::Index>(costs.size()));
  rewards_[slot] = reward;
  ++count_;
  // The oldest step's window s_t .. s_{t+n} is complete: it ends at this step's s'.
  if (count_ == n_) emit_oldest(next_observation, terminated, buffer);
  if (episode_ends) {
    while (count_ > 0) emit_oldest(next_observation, terminated, buffer);
    first_ = 0;
  }
}

void NStepAccumulator::flush(std::span<const double> next_observation, ReplayBuffer& buffer) {
  while (count_ > 0) emit_oldest(next_observation, false, buffer);
  first_ = 0;
}

}  // namespace bsg::algos
