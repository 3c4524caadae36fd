#include "algos/core/buffer.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace bsg::algos {
namespace {

// A_t = sum_l (gamma lambda)^l delta_t+l, backwards over one path, with
// delta_t = r_t + gamma V_t+1 - V_t and V_T = v_last.
void discounted_advantages(const Eigen::Ref<const Eigen::VectorXd>& rewards,
                           const Eigen::Ref<const Eigen::VectorXd>& values, double last_value, double gamma,
                           double lambda, Eigen::Ref<Eigen::VectorXd> advantages) {
  double running = 0.0;
  double next_value = last_value;
  for (Eigen::Index t = rewards.size() - 1; t >= 0; --t) {
    const double delta = rewards[t] + gamma * next_value - values[t];  // delta_t
    running = delta + gamma * lambda * running;                         // A_t = delta_t + gamma lambda A_t+1
    advantages[t] = running;
    next_value = values[t];
  }
}

}  // namespace

Buffer::Buffer(Eigen::Index capacity, int observation_size, int action_size, BufferOptions options)
    : options_(options) {
  if (capacity <= 0) throw std::invalid_argument("Buffer: capacity must be positive, got " + std::to_string(capacity));
  if (observation_size <= 0 || action_size <= 0) {
    throw std::invalid_argument("Buffer: observation_size (" + std::to_string(observation_size) +
                                ") and action_size (" + std::to_string(action_size) + ") must be positive");
  }
  if (!(options.gamma >= 0.0 && options.gamma <= 1.0) || !(options.lam >= 0.0 && options.lam <= 1.0) ||
      !(options.lam_c >= 0.0 && options.lam_c <= 1.0)) {
    throw std::invalid_argument("Buffer: gamma, lam and lam_c must lie in [0, 1], got " +
                                std::to_string(options.gamma) + ", " + std::to_string(options.lam) + ", " +
                                std::to_string(options.lam_c));
  }
  if (options.constraint_count < 1) {
    throw std::invalid_argument("Buffer: constraint_count must be at least 1, got " +
                                std::to_string(options.constraint_count));
  }
  observations_.setZero(capacity, observation_size);
  actions_.setZero(capacity, action_size);
  for (Eigen::VectorXd* v : {&rewards_, &values_, &log_probs_, &advantages_, &value_targets_, &discounted_returns_}) {
    v->setZero(capacity);
  }
  episode_steps_.setZero(capacity);
  for (Eigen::MatrixXd* m : {&costs_, &cost_values_, &cost_advantages_, &cost_value_targets_}) {
    m->setZero(capacity, options.constraint_count);
  }
  epoch_constraint_costs_.setZero(options.constraint_count);
  current_episode_.constraint_costs.assign(static_cast<std::size_t>(options.constraint_count), 0.0);
}

void Buffer::reset() {
  size_ = 0;
  path_start_ = 0;
  start_episode();
  episodes_.clear();
  epoch_cost_ = 0.0;
  epoch_constraint_costs_.setZero();
}

void Buffer::start_episode() {
  current_episode_.episode_return = 0.0;
  current_episode_.episode_cost = 0.0;
  current_episode_.episode_length = 0;
  std::fill(current_episode_.constraint_costs.begin(), current_episode_.constraint_costs.end(), 0.0);
  current_episode_.learner_return = 0.0;
  current_episode_.budget_spent = false;
}

void Buffer::shape_last_reward(double learner_reward, bool budget_spent) {
  if (current_path_length() == 0) throw std::logic_error("Buffer::shape_last_reward: no step stored in this path");
  rewards_[size_ - 1] = learner_reward;
  current_episode_.learner_return += learner_reward;
  current_episode_.budget_spent = current_episode_.budget_spent || budget_spent;
}

void Buffer::store(const Eigen::Ref<const Eigen::VectorXd>& observation,
                   const Eigen::Ref<const Eigen::VectorXd>& action, double reward, double cost, double value,
                   double cost_value, double log_prob) {
  check_single_constraint("store");
  const Eigen::Matrix<double, 1, 1> costs(cost);
  const Eigen::Matrix<double, 1, 1> cost_values(cost_value);
  store(observation, action, reward, cost, costs, value, cost_values, log_prob);
}

void Buffer::check_single_constraint(const char* where) const {
  if (constraint_count() != 1) {
    throw std::invalid_argument(std::string("Buffer::") + where + ": the scalar form serves one constraint, the buffer has " +
                                std::to_string(constraint_count()));
  }
}

void Buffer::store(const Eigen::Ref<const Eigen::VectorXd>& observation,
                   const Eigen::Ref<const Eigen::VectorXd>& action, double reward, double cost,
                   const Eigen::Ref<const Eigen::VectorXd>& constraint_costs, double value,
                   const Eigen::Ref<const Eigen::VectorXd>& cost_values, double log_prob) {
  if (full()) {
    throw std::length_error("Buffer::store: buffer is full (" + std::to_string(capacity()) + " steps)");
  }
  if (observation.size() != observations_.cols()) {
    throw std::invalid_argument("Buffer::store: observation has " + std::to_string(observation.size()) +
                                " entries, expected " + std::to_string(observations_.cols()));
  }
  if (action.size() != actions_.cols()) {
    throw std::invalid_argument("Buffer::store: action has " + std::to_string(action.size()) +
                                " entries, expected " + std::to_string(actions_.cols()));
  }
  if (constraint_costs.size() != costs_.cols() || cost_values.size() != costs_.cols()) {
    throw std::invalid_argument("Buffer::store: " + std::to_string(constraint_costs.size()) + " constraint costs and " +
                                std::to_string(cost_values.size()) + " cost values, expected " +
                                std::to_string(costs_.cols()) + " of each");
  }
  observations_.row(size_) = observation.transpose();
  actions_.row(size_) = action.transpose();
  rewards_[size_] = reward;
  costs_.row(size_) = constraint_costs.transpose();
  values_[size_] = value;
  cost_values_.row(size_) = cost_values.transpose();
  log_probs_[size_] = log_prob;
  episode_steps_[size_] = current_episode_.episode_length;
  ++size_;
  current_episode_.episode_return += reward;
  current_episode_.episode_cost += cost;
  ++current_episode_.episode_length;
  epoch_cost_ += cost;
  for (Eigen::Index i = 0; i < constraint_costs.size(); ++i) {
    current_episode_.constraint_costs[static_cast<std::size_t>(i)] += constraint_costs[i];
    epoch_constraint_costs_[i] += constraint_costs[i];
  }
}

void Buffer::finish_path(double last_value, double last_cost_value, std::optional<double> reward_scale_std,
                         PathEnd end) {
  check_single_constraint("finish_path");
  finish_path(last_value, Eigen::Matrix<double, 1, 1>(last_cost_value), reward_scale_std, end);
}

void Buffer::finish_path(double last_value, const Eigen::Ref<const Eigen::VectorXd>& last_cost_values,
                         std::optional<double> reward_scale_std, PathEnd end) {
  if (last_cost_values.size() != costs_.cols()) {
    throw std::invalid_argument("Buffer::finish_path: " + std::to_string(last_cost_values.size()) +
                                " bootstrap cost values, expected " + std::to_string(costs_.cols()));
  }
  const Eigen::Index start = path_start_;
  const Eigen::Index length = size_ - path_start_;
  if (length == 0) throw std::logic_error("Buffer::finish_path: the current path is empty");
  if (reward_scale_std && !(*reward_scale_std >= 0.0)) {
    throw std::invalid_argument("Buffer::finish_path: reward_scale_std must be >= 0, got " +
                                std::to_string(*reward_scale_std));
  }
  const double gamma = options_.gamma;

  // Rewards for GAE: r~_t = clip(r_t / (s_ret + 1e-5), -10, 10) under reward scaling (docs/algorithms.md#reward-scaling).
  // The scaled rewards go into the target buffer first, which is then overwritten.
  auto scaled_rewards = value_targets_.segment(start, length);
  scaled_rewards = rewards_.segment(start, length);
  if (reward_scale_std) {
    scaled_rewards = (scaled_rewards / (*reward_scale_std + kStdEpsilon)).cwiseMax(-kRewardClip).cwiseMin(kRewardClip);
  }
  discounted_advantages(scaled_rewards, values_.segment(start, length), last_value, gamma, options_.lam,
                        advantages_.segment(start, length));
  value_targets_.segment(start, length) = advantages_.segment(start, length) + values_.segment(start, length);  // R_t

  for (Eigen::Index i = 0; i < costs_.cols(); ++i) {  // each constraint's own GAE
    discounted_advantages(costs_.col(i).segment(start, length), cost_values_.col(i).segment(start, length),
                          last_cost_values[i], gamma, options_.lam_c, cost_advantages_.col(i).segment(start, length));
    cost_value_targets_.col(i).segment(start, length) =
        cost_advantages_.col(i).segment(start, length) + cost_values_.col(i).segment(start, length);  // R^Ci_t
  }

  // G_t = sum_l gamma^l r_t+l over raw rewards followed by v_last (Q5), or by
  // v_last in raw units: V learns scaled values, V = G / (s_ret + 1e-5).
  double running_return = last_value;
  if (options_.consistent_return_statistic && reward_scale_std) running_return *= *reward_scale_std + kStdEpsilon;
  for (Eigen::Index t = start + length - 1; t >= start; --t) {
    running_return = rewards_[t] + gamma * running_return;
    discounted_returns_[t] = running_return;
  }

  if (end == PathEnd::episode_end) episodes_.push_back(current_episode_);
  start_episode();
  path_start_ = size_;
}

void Buffer::check_ready() const {
  if (!full()) {
    throw std::logic_error("Buffer: holds " + std::to_string(size_) + " of " + std::to_string(capacity()) +
                           " steps; the epoch's data is read only when the buffer is full");
  }
  if (path_start_ != size_) throw std::logic_error("Buffer: the last path is not finished (call finish_path)");
}

}  // namespace bsg::algos
