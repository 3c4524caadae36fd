// The replay buffer of the off-policy learners (docs/algorithms.md#off-policy-learners): a ring of
// transitions (s, a, R, C_1..C_m, s', discount, terminal) of fixed capacity; once full, each new
// transition overwrites the oldest. R and C_i are (n-step) sums of discounted rewards and costs and
// `discount` is gamma^k for the k steps they span (n_step_returns.h), so the critics' targets are
//   y = R + discount (1 - terminal) Q'(s', a')
// whatever n: a time-limit truncation keeps terminal = 0 and bootstraps, a termination does not.
//
// Storage: observations and actions in float32 (the learners' default arithmetic; a 10^6-transition
// buffer of a 50-dimensional observation then takes 0.4 GB, not 0.8), rewards, costs and discounts
// in float64. bytes_per_transition() says how many bytes a transition takes.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "common/random.h"

namespace bsg::algos {

// One batch of transitions, one per row; sized by ReplayBuffer::gather.
struct ReplayBatch {
  Eigen::MatrixXd observations;       // N x |S|
  Eigen::MatrixXd actions;            // N x |A|
  Eigen::VectorXd rewards;            // N: R
  Eigen::MatrixXd costs;              // N x m: C_i
  Eigen::MatrixXd next_observations;  // N x |S|: s' (the n-th next state)
  Eigen::VectorXd discounts;          // N: gamma^k
  Eigen::VectorXd terminals;          // N: 1 if the episode terminated within the k steps, else 0
  Eigen::Index rows() const { return rewards.size(); }
};

class ReplayBuffer {
 public:
  // Throws std::invalid_argument unless every size is positive (cost_count may be 0).
  ReplayBuffer(int observation_size, int action_size, int cost_count, std::int64_t capacity);

  int observation_size() const { return observation_size_; }
  int action_size() const { return action_size_; }
  int cost_count() const { return cost_count_; }
  std::int64_t capacity() const { return capacity_; }
  std::int64_t size() const { return size_; }             // transitions held, at most capacity
  std::int64_t total_added() const { return total_added_; }  // transitions ever added
  std::int64_t next_slot() const { return next_slot_; }    // where the next one goes
  static std::int64_t bytes_per_transition(int observation_size, int action_size, int cost_count);

  // Stores one transition in the next slot (overwriting the oldest once full). No allocation.
  void add(std::span<const double> observation, std::span<const double> action, double reward,
           std::span<const double> costs, std::span<const double> next_observation, double discount, bool terminal);

  // Copies the transitions in `slots` (each in [0, size)) into `batch`, resizing it if needed.
  void gather(std::span<const std::int64_t> slots, ReplayBatch& batch) const;
  // `batch_size` slots drawn uniformly with replacement from [0, size) into `slots`, then gather.
  // Throws std::logic_error if the buffer is empty.
  void sample(int batch_size, Rng& rng, std::vector<std::int64_t>& slots, ReplayBatch& batch) const;

  // The append-only record (algos/training/replay_buffer_log.h): transition k of the run (k counts
  // every add, from 0) lives in slot k mod capacity while it is held. write_transitions appends the
  // bytes of transitions [first, first + count), which must all be held; restore_transitions puts
  // such bytes back into their slots; restore_counters then sets the counters for `total_added`
  // transitions added (size min(total_added, capacity), next slot total_added mod capacity).
  void write_transitions(std::int64_t first, std::int64_t count, std::string& bytes) const;
  void restore_transitions(std::int64_t first, std::int64_t count, std::string_view bytes);
  void restore_counters(std::int64_t total_added);

 private:
  using RowMatrixF = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  using RowMatrixD = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  int observation_size_;
  int action_size_;
  int cost_count_;
  std::int64_t capacity_;
  std::int64_t size_ = 0;
  std::int64_t next_slot_ = 0;
  std::int64_t total_added_ = 0;
  RowMatrixF observations_;
  RowMatrixF next_observations_;
  RowMatrixF actions_;
  RowMatrixD scalars_;  // per slot: R, discount, terminal, C_1..C_m
};

}  // namespace bsg::algos
