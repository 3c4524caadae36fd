#include "algos/off_policy/replay_buffer.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>

namespace bsg::algos {
namespace {

constexpr Eigen::Index kRewardColumn = 0;
constexpr Eigen::Index kDiscountColumn = 1;
constexpr Eigen::Index kTerminalColumn = 2;
constexpr Eigen::Index kFirstCostColumn = 3;

template <typename Row>
void copy_row(std::span<const double> values, Row row) {
  for (Eigen::Index j = 0; j < row.size(); ++j) row(j) = static_cast<float>(values[static_cast<std::size_t>(j)]);
}

}  // namespace

ReplayBuffer::ReplayBuffer(int observation_size, int action_size, int cost_count, std::int64_t capacity)
    : observation_size_(observation_size), action_size_(action_size), cost_count_(cost_count), capacity_(capacity) {
  if (observation_size < 1 || action_size < 1 || cost_count < 0 || capacity < 1) {
    throw std::invalid_argument("ReplayBuffer: sizes must be positive (observation " +
                                std::to_string(observation_size) + ", action " + std::to_string(action_size) +
                                ", costs " + std::to_string(cost_count) + ", capacity " + std::to_string(capacity) +
                                ")");
  }
  observations_.resize(capacity, observation_size);
  next_observations_.resize(capacity, observation_size);
  actions_.resize(capacity, action_size);
  scalars_.resize(capacity, kFirstCostColumn + cost_count);
}

std::int64_t ReplayBuffer::bytes_per_transition(int observation_size, int action_size, int cost_count) {
  return 4 * (2 * static_cast<std::int64_t>(observation_size) + action_size) + 8 * (kFirstCostColumn + cost_count);
}

void ReplayBuffer::add(std::span<const double> observation, std::span<const double> action, double reward,
                       std::span<const double> costs, std::span<const double> next_observation, double discount,
                       bool terminal) {
  if (static_cast<int>(observation.size()) != observation_size_ ||
      static_cast<int>(next_observation.size()) != observation_size_ ||
      static_cast<int>(action.size()) != action_size_ || static_cast<int>(costs.size()) != cost_count_) {
    throw std::invalid_argument("ReplayBuffer::add: a transition of sizes (" + std::to_string(observation.size()) +
                                ", " + std::to_string(action.size()) + ", " + std::to_string(costs.size()) + ", " +
                                std::to_string(next_observation.size()) + "), expected (" +
                                std::to_string(observation_size_) + ", " + std::to_string(action_size_) + ", " +
                                std::to_string(cost_count_) + ", " + std::to_string(observation_size_) + ")");
  }
  const std::int64_t slot = next_slot_;
  copy_row(observation, observations_.row(slot));
  copy_row(next_observation, next_observations_.row(slot));
  copy_row(action, actions_.row(slot));
  scalars_(slot, kRewardColumn) = reward;
  scalars_(slot, kDiscountColumn) = discount;
  scalars_(slot, kTerminalColumn) = terminal ? 1.0 : 0.0;
  for (int i = 0; i < cost_count_; ++i) scalars_(slot, kFirstCostColumn + i) = costs[static_cast<std::size_t>(i)];
  next_slot_ = (next_slot_ + 1) % capacity_;  // the ring wraps: the oldest slot is overwritten next
  if (size_ < capacity_) ++size_;
  ++total_added_;
}

void ReplayBuffer::gather(std::span<const std::int64_t> slots, ReplayBatch& batch) const {
  const Eigen::Index rows = static_cast<Eigen::Index>(slots.size());
  if (batch.rewards.size() != rows || batch.observations.cols() != observation_size_ ||
      batch.costs.cols() != cost_count_) {
    batch.observations.resize(rows, observation_size_);
    batch.next_observations.resize(rows, observation_size_);
    batch.actions.resize(rows, action_size_);
    batch.rewards.resize(rows);
    batch.costs.resize(rows, cost_count_);
    batch.discounts.resize(rows);
    batch.terminals.resize(rows);
  }
  for (Eigen::Index r = 0; r < rows; ++r) {
    const std::int64_t slot = slots[static_cast<std::size_t>(r)];
    if (slot < 0 || slot >= size_) {
      throw std::out_of_range("ReplayBuffer::gather: slot " + std::to_string(slot) + " outside [0, " +
                              std::to_string(size_) + ")");
    }
    batch.observations.row(r) = observations_.row(slot).cast<double>();
    batch.next_observations.row(r) = next_observations_.row(slot).cast<double>();
    batch.actions.row(r) = actions_.row(slot).cast<double>();
    batch.rewards(r) = scalars_(slot, kRewardColumn);
    batch.discounts(r) = scalars_(slot, kDiscountColumn);
    batch.terminals(r) = scalars_(slot, kTerminalColumn);
    for (int i = 0; i < cost_count_; ++i) batch.costs(r, i) = scalars_(slot, kFirstCostColumn + i);
  }
}

void ReplayBuffer::sample(int batch_size, Rng& rng, std::vector<std::int64_t>& slots, ReplayBatch& batch) const {
  if (size_ == 0) throw std::logic_error("ReplayBuffer::sample: the buffer is empty");
  slots.resize(static_cast<std::size_t>(batch_size));  // no allocation once sized
  for (std::int64_t& slot : slots) slot = static_cast<std::int64_t>(uniform_index(rng, static_cast<std::uint64_t>(size_)));
  gather(slots, batch);
}

void ReplayBuffer::write_transitions(std::int64_t first, std::int64_t count, std::string& bytes) const {
  if (count < 0 || first < total_added_ - size_ || first + count > total_added_) {
    throw std::out_of_range("ReplayBuffer::write_transitions: transitions [" + std::to_string(first) + ", " +
                            std::to_string(first + count) + ") are not all held (held: [" +
                            std::to_string(total_added_ - size_) + ", " + std::to_string(total_added_) + "))");
  }
  const auto append_row = [&](const auto& matrix, std::int64_t slot) {
    using Scalar = typename std::decay_t<decltype(matrix)>::Scalar;
    bytes.append(reinterpret_cast<const char*>(matrix.row(slot).data()),
                 static_cast<std::size_t>(matrix.cols()) * sizeof(Scalar));
  };
  for (std::int64_t k = first; k < first + count; ++k) {
    const std::int64_t slot = k % capacity_;
    append_row(observations_, slot);
    append_row(next_observations_, slot);
    append_row(actions_, slot);
    append_row(scalars_, slot);
  }
}

void ReplayBuffer::restore_transitions(std::int64_t first, std::int64_t count, std::string_view bytes) {
  const std::int64_t row_bytes = bytes_per_transition(observation_size_, action_size_, cost_count_);
  if (first < 0 || count < 0 || static_cast<std::int64_t>(bytes.size()) != count * row_bytes) {
    throw std::invalid_argument("ReplayBuffer::restore_transitions: " + std::to_string(bytes.size()) +
                                " bytes for " + std::to_string(count) + " transitions of " + std::to_string(row_bytes));
  }
  std::size_t position = 0;
  const auto read_row = [&](auto& matrix, std::int64_t slot) {
    using Scalar = typename std::decay_t<decltype(matrix)>::Scalar;
    const std::size_t length = static_cast<std::size_t>(matrix.cols()) * sizeof(Scalar);
    std::memcpy(matrix.row(slot).data(), bytes.data() + position, length);
    position += length;
  };
  for (std::int64_t k = first; k < first + count; ++k) {
    const std::int64_t slot = k % capacity_;
    read_row(observations_, slot);
    read_row(next_observations_, slot);
    read_row(actions_, slot);
    read_row(scalars_, slot);
  }
}

void ReplayBuffer::restore_counters(std::int64_t total_added) {
  if (total_added < 0) throw std::invalid_argument("ReplayBuffer::restore_counters: negative count");
  total_added_ = total_added;
  size_ = std::min(total_added, capacity_);
  next_slot_ = total_added % capacity_;
}

}  // namespace bsg::algos
