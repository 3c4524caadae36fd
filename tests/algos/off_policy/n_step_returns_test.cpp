// n-step transitions on a hand-made trajectory (gamma 0.5): the sums, the discounts gamma^k, the
// n-th next state, and terminal set by a termination only, never by a truncation or an epoch cut.
#include "algos/off_policy/n_step_returns.h"

#include <gtest/gtest.h>

#include <vector>

namespace bsg::algos {
namespace {

// Step t: s_t = 10 t, a_t = t, r = (1, 2, 4, 8)[t], c = (1, 0, 1, 1)[t], s_{t+1} = 10 (t + 1).
void play(NStepAccumulator& accumulator, ReplayBuffer& buffer, int steps, bool terminated_at_end) {
  const double rewards[] = {1, 2, 4, 8};
  const double costs[] = {1, 0, 1, 1};
  for (int t = 0; t < steps; ++t) {
    const std::vector<double> s{10.0 * t}, a{double(t)}, c{costs[t]}, next{10.0 * (t + 1)};
    const bool last = t + 1 == steps;
    accumulator.add(s, a, rewards[t], c, next, last && terminated_at_end, last, buffer);
  }
}

ReplayBatch everything(const ReplayBuffer& buffer) {
  std::vector<std::int64_t> slots;
  for (std::int64_t k = 0; k < buffer.size(); ++k) slots.push_back(k);
  ReplayBatch batch;
  buffer.gather(slots, batch);
  return batch;
}

TEST(NStepReturns, TwoStepSumsOfATruncatedEpisodeBootstrap) {
  ReplayBuffer buffer(1, 1, 1, 16);
  NStepAccumulator accumulator(2, 0.5, 1, 1, 1);
  play(accumulator, buffer, 4, /*terminated_at_end=*/false);
  const ReplayBatch b = everything(buffer);
  ASSERT_EQ(b.rows(), 4);
  // t0: 1 + 0.5*2 = 2, cost 1 + 0.5*0 = 1, s' = s2, gamma^2
  // t1: 2 + 0.5*4 = 4, cost 0 + 0.5*1 = 0.5, s' = s3
  // t2: 4 + 0.5*8 = 8, cost 1 + 0.5*1 = 1.5, s' = s4
  // t3: the episode's last step alone: 8, cost 1, s' = s4, gamma^1
  const double R[] = {2, 4, 8, 8}, C[] = {1, 0.5, 1.5, 1}, next[] = {20, 30, 40, 40}, discount[] = {0.25, 0.25, 0.25, 0.5};
  for (int t = 0; t < 4; ++t) {
    SCOPED_TRACE(t);
    EXPECT_DOUBLE_EQ(b.observations(t, 0), 10.0 * t);
    EXPECT_DOUBLE_EQ(b.actions(t, 0), t);
    EXPECT_DOUBLE_EQ(b.rewards(t), R[t]);
    EXPECT_DOUBLE_EQ(b.costs(t, 0), C[t]);
    EXPECT_DOUBLE_EQ(b.next_observations(t, 0), next[t]);
    EXPECT_DOUBLE_EQ(b.discounts(t), discount[t]);
    EXPECT_EQ(b.terminals(t), 0.0);  // truncated: every transition bootstraps
  }
  EXPECT_EQ(accumulator.pending(), 0);
}

TEST(NStepReturns, ATerminationEndsTheTransitionsThatReachIt) {
  ReplayBuffer buffer(1, 1, 1, 16);
  NStepAccumulator accumulator(2, 0.5, 1, 1, 1);
  play(accumulator, buffer, 4, /*terminated_at_end=*/true);
  const ReplayBatch b = everything(buffer);
  ASSERT_EQ(b.rows(), 4);
  // t0 and t1 end before the termination; t2 (s' = s4) and t3 reach it.
  EXPECT_EQ(b.terminals(0), 0.0);
  EXPECT_EQ(b.terminals(1), 0.0);
  EXPECT_EQ(b.terminals(2), 1.0);
  EXPECT_EQ(b.terminals(3), 1.0);
  EXPECT_DOUBLE_EQ(b.rewards(3), 8.0);
}

TEST(NStepReturns, AnEpisodeShorterThanNLeavesWithWhatItHas) {
  ReplayBuffer buffer(1, 1, 1, 16);
  NStepAccumulator accumulator(3, 0.5, 1, 1, 1);
  play(accumulator, buffer, 2, /*terminated_at_end=*/true);
  // a second episode starts clean
  play(accumulator, buffer, 1, /*terminated_at_end=*/false);
  const ReplayBatch b = everything(buffer);
  ASSERT_EQ(b.rows(), 3);
  EXPECT_DOUBLE_EQ(b.rewards(0), 1 + 0.5 * 2);
  EXPECT_DOUBLE_EQ(b.discounts(0), 0.25);
  EXPECT_DOUBLE_EQ(b.next_observations(0, 0), 20.0);
  EXPECT_EQ(b.terminals(0), 1.0);
  EXPECT_DOUBLE_EQ(b.rewards(1), 2.0);
  EXPECT_DOUBLE_EQ(b.discounts(1), 0.5);
  EXPECT_EQ(b.terminals(1), 1.0);
  EXPECT_DOUBLE_EQ(b.rewards(2), 1.0);
  EXPECT_DOUBLE_EQ(b.observations(2, 0), 0.0);
  EXPECT_EQ(b.terminals(2), 0.0);
}

TEST(NStepReturns, OneStepIsTheTransitionItself) {
  ReplayBuffer buffer(1, 1, 1, 16);
  NStepAccumulator accumulator(1, 0.99, 1, 1, 1);
  play(accumulator, buffer, 3, false);
  const ReplayBatch b = everything(buffer);
  ASSERT_EQ(b.rows(), 3);
  EXPECT_DOUBLE_EQ(b.rewards(2), 4.0);
  EXPECT_DOUBLE_EQ(b.discounts(2), 0.99);
  EXPECT_DOUBLE_EQ(b.next_observations(1, 0), 20.0);
}

TEST(NStepReturns, RejectsBadSettings) {
  EXPECT_THROW(NStepAccumulator(0, 0.9, 1, 1, 1), std::invalid_argument);
  EXPECT_THROW(NStepAccumulator(2, 0.0, 1, 1, 1), std::invalid_argument);
  EXPECT_THROW(NStepAccumulator(2, 1.5, 1, 1, 1), std::invalid_argument);
}

}  // namespace
}  // namespace bsg::algos
