// The append-only replay buffer record (algos/training/replay_buffer_log.h): appends only what is
// new, rewrites itself once it holds more than twice the capacity, restores the buffer exactly as
// it was after a given count (dropping later and torn records), and names what is missing.
#include "algos/training/replay_buffer_log.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <vector>

#include "../../test_support.h"
#include "common/binary_io.h"

namespace bsg::algos {
namespace {

void add(ReplayBuffer& buffer, int count) {
  for (int i = 0; i < count; ++i) {
    const double k = static_cast<double>(buffer.total_added());
    const std::vector<double> observation{k, -k}, action{k / 100}, costs{k / 2}, next{k + 1, -k - 1};
    buffer.add(observation, action, k, costs, next, 0.9, static_cast<long long>(k) % 7 == 0);
  }
}

// Every held slot of both buffers holds the same transition.
bool same_contents(const ReplayBuffer& a, const ReplayBuffer& b) {
  if (a.size() != b.size() || a.total_added() != b.total_added() || a.next_slot() != b.next_slot()) return false;
  std::vector<std::int64_t> slots;
  for (std::int64_t k = 0; k < a.size(); ++k) slots.push_back(k);
  ReplayBatch x, y;
  a.gather(slots, x);
  b.gather(slots, y);
  return x.observations == y.observations && x.actions == y.actions && x.rewards == y.rewards && x.costs == y.costs &&
         x.next_observations == y.next_observations && x.terminals == y.terminals;
}

TEST(ReplayBufferLog, AppendsWhatIsNewAndRewritesBeyondTwiceTheCapacity) {
  testing::TemporaryDirectory dir;
  const auto path = replay_buffer_log_path(dir.path(), 0);
  EXPECT_EQ(path.filename(), "replay_buffer.r0.log");
  ReplayBuffer buffer(2, 1, 1, 10);
  ReplayBufferLog log(path);
  const std::int64_t row = ReplayBuffer::bytes_per_transition(2, 1, 1);
  constexpr std::int64_t kHeader = 16, kRecordHeader = 24;
  add(buffer, 4);
  log.append(buffer);  // new file: header + one record of 4
  EXPECT_EQ(static_cast<std::int64_t>(std::filesystem::file_size(path)), kHeader + kRecordHeader + 4 * row);
  add(buffer, 6);
  log.append(buffer);  // 6 more appended
  EXPECT_EQ(static_cast<std::int64_t>(std::filesystem::file_size(path)), kHeader + 2 * kRecordHeader + 10 * row);
  add(buffer, 25);  // 35 in all, 10 of them held: the file would hold 10 + 10 = 20, not more than 2 x 10
  log.append(buffer);
  EXPECT_EQ(static_cast<std::int64_t>(std::filesystem::file_size(path)), kHeader + 3 * kRecordHeader + 20 * row);
  add(buffer, 1);  // 21 > 20: rewritten with the 10 held
  log.append(buffer);
  EXPECT_EQ(static_cast<std::int64_t>(std::filesystem::file_size(path)), kHeader + kRecordHeader + 10 * row);
  ReplayBuffer restored(2, 1, 1, 10);
  ReplayBufferLog reader(path);
  reader.restore(restored, 36);
  EXPECT_TRUE(same_contents(restored, buffer));
}

TEST(ReplayBufferLog, RestoresAnEarlierCountAndCutsTheRecordsAfterIt) {
  testing::TemporaryDirectory dir;
  const auto path = replay_buffer_log_path(dir.path(), 3);
  ReplayBuffer buffer(2, 1, 1, 8);
  ReplayBufferLog log(path);
  add(buffer, 5);
  log.append(buffer);
  add(buffer, 6);  // 11: transitions 3..10 held
  log.append(buffer);
  const auto size_at_11 = std::filesystem::file_size(path);
  ReplayBuffer expected(2, 1, 1, 8);
  add(expected, 11);
  add(buffer, 4);
  log.append(buffer);  // a record the checkpoint (at 11) never saw
  testing::write_text_file(path, testing::read_text_file(path) + "torn");
  ReplayBuffer restored(2, 1, 1, 8);
  ReplayBufferLog reader(path);
  reader.restore(restored, 11);
  EXPECT_TRUE(same_contents(restored, expected));
  EXPECT_EQ(std::filesystem::file_size(path), size_at_11);
  EXPECT_EQ(reader.logged_until(), 11);
  // a record the checkpoint needs and the file lacks is an error naming the file
  ReplayBuffer again(2, 1, 1, 8);
  ReplayBufferLog short_log(path);
  EXPECT_THROW(short_log.restore(again, 12), CheckpointError);
  ReplayBuffer other_sizes(3, 1, 1, 8);
  EXPECT_THROW(ReplayBufferLog(path).restore(other_sizes, 11), CheckpointError);
}

}  // namespace
}  // namespace bsg::algos
