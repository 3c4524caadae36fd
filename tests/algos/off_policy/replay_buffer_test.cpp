// The replay buffer: transitions come back as stored, the ring overwrites the oldest once full,
// sampling draws only held slots, and a save/load round trip keeps every byte.
#include "algos/off_policy/replay_buffer.h"

#include <gtest/gtest.h>

#include <set>
#include <string>
#include <vector>

namespace bsg::algos {
namespace {

// Transition k: observation (k, -k), action (k/8), reward k, costs (k/2, 2k), next (k+1, -k-1).
void add_transition(ReplayBuffer& buffer, int k, bool terminal = false) {
  const std::vector<double> observation{double(k), -double(k)};
  const std::vector<double> action{k / 8.0};
  const std::vector<double> costs{k / 2.0, 2.0 * k};
  const std::vector<double> next{k + 1.0, -k - 1.0};
  buffer.add(observation, action, k, costs, next, 0.5, terminal);
}

TEST(ReplayBuffer, GivesBackWhatWasStored) {
  ReplayBuffer buffer(2, 1, 2, 10);
  for (int k = 0; k < 4; ++k) add_transition(buffer, k, k == 3);
  EXPECT_EQ(buffer.size(), 4);
  ReplayBatch batch;
  const std::vector<std::int64_t> slots{3, 1};
  buffer.gather(slots, batch);
  ASSERT_EQ(batch.rows(), 2);
  EXPECT_EQ(batch.observations(0, 0), 3.0);
  EXPECT_EQ(batch.observations(0, 1), -3.0);
  EXPECT_EQ(batch.actions(0, 0), 3.0 / 8.0);
  EXPECT_EQ(batch.rewards(0), 3.0);
  EXPECT_EQ(batch.costs(0, 0), 1.5);
  EXPECT_EQ(batch.costs(0, 1), 6.0);
  EXPECT_EQ(batch.next_observations(0, 0), 4.0);
  EXPECT_EQ(batch.discounts(0), 0.5);
  EXPECT_EQ(batch.terminals(0), 1.0);
  EXPECT_EQ(batch.rewards(1), 1.0);
  EXPECT_EQ(batch.terminals(1), 0.0);
}

TEST(ReplayBuffer, WrapsAroundOverwritingTheOldest) {
  ReplayBuffer ring(2, 1, 2, 3);
  for (int k = 0; k < 5; ++k) add_transition(ring, k);
  // capacity 3 after 5 adds: slots 0, 1, 2 hold transitions 3, 4, 2; the next goes to slot 2.
  EXPECT_EQ(ring.size(), 3);
  EXPECT_EQ(ring.total_added(), 5);
  EXPECT_EQ(ring.next_slot(), 2);
  ReplayBatch batch;
  const std::vector<std::int64_t> slots{0, 1, 2};
  ring.gather(slots, batch);
  EXPECT_EQ(batch.rewards(0), 3.0);
  EXPECT_EQ(batch.rewards(1), 4.0);
  EXPECT_EQ(batch.rewards(2), 2.0);
  add_transition(ring, 5);
  ring.gather(slots, batch);
  EXPECT_EQ(batch.rewards(2), 5.0);
  const std::vector<std::int64_t> outside{3};
  EXPECT_THROW(ring.gather(outside, batch), std::out_of_range);
}

TEST(ReplayBuffer, SamplesOnlyHeldSlots) {
  ReplayBuffer buffer(2, 1, 2, 100);
  ReplayBatch batch;
  std::vector<std::int64_t> slots;
  Rng rng(1);
  EXPECT_THROW(buffer.sample(4, rng, slots, batch), std::logic_error);
  for (int k = 0; k < 5; ++k) add_transition(buffer, k);
  std::set<double> seen;
  for (int draw = 0; draw < 50; ++draw) {
    buffer.sample(8, rng, slots, batch);
    for (Eigen::Index r = 0; r < batch.rows(); ++r) seen.insert(batch.rewards(r));
  }
  EXPECT_EQ(seen, (std::set<double>{0, 1, 2, 3, 4}));
}

TEST(ReplayBuffer, WrittenTransitionsRestoreTheRingExactly) {
  ReplayBuffer buffer(2, 1, 2, 4);
  for (int k = 0; k < 6; ++k) add_transition(buffer, k, k % 2 == 0);
  // transitions 2..5 are held (slots 2, 3, 0, 1); write 3..5 and 2 separately, restore in any order
  std::string late, early;
  buffer.write_transitions(3, 3, late);
  buffer.write_transitions(2, 1, early);
  EXPECT_THROW(buffer.write_transitions(1, 1, early), std::out_of_range);  // overwritten already
  EXPECT_EQ(static_cast<std::int64_t>(late.size()), 3 * ReplayBuffer::bytes_per_transition(2, 1, 2));
  ReplayBuffer restored(2, 1, 2, 4);
  restored.restore_transitions(3, 3, late);
  restored.restore_transitions(2, 1, early);
  restored.restore_counters(6);
  EXPECT_EQ(restored.size(), 4);
  EXPECT_EQ(restored.next_slot(), buffer.next_slot());
  EXPECT_EQ(restored.total_added(), 6);
  ReplayBatch a, b;
  const std::vector<std::int64_t> slots{0, 1, 2, 3};
  buffer.gather(slots, a);
  restored.gather(slots, b);
  EXPECT_EQ(a.observations, b.observations);
  EXPECT_EQ(a.next_observations, b.next_observations);
  EXPECT_EQ(a.actions, b.actions);
  EXPECT_EQ(a.rewards, b.rewards);
  EXPECT_EQ(a.costs, b.costs);
  EXPECT_EQ(a.terminals, b.terminals);
}

TEST(ReplayBuffer, CountsBytesPerTransition) {
  // float32 observation, next observation and action; float64 reward, discount, terminal and costs.
  EXPECT_EQ(ReplayBuffer::bytes_per_transition(7, 2, 1), 4 * (7 + 7 + 2) + 8 * (3 + 1));
}

}  // namespace
}  // namespace bsg::algos
