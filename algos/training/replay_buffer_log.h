// The append-only record of a rank's replay buffer (docs/algorithms.md#off-policy-checkpoints):
// replay_buffer.r<rank>.log in the run directory. A checkpoint appends only the transitions added
// since the previous one (and fsyncs), so a 10^6-transition buffer is not rewritten at every save;
// when the file holds more than twice the buffer's capacity it is rewritten once with the held
// transitions alone (atomically). checkpoint.bin names how many transitions its state has seen; on
// resume the buffer is rebuilt from the records up to that count and anything after it (written by
// a run killed before its checkpoint.bin) is cut off the file.
//
// Layout: "BSGRBLOG" (8 bytes), u32 format 1, u32 bytes per transition; then records, each
//   u64 first transition, u64 count, u64 FNV-1a 64 of the payload, payload (count transitions as
//   ReplayBuffer::write_transitions writes them);
// all integers little-endian. A torn last record (a crash during an append) fails its checksum or
// its length and is dropped like a record after the checkpoint.
#pragma once

#include <cstdint>
#include <filesystem>

#include "algos/off_policy/replay_buffer.h"

namespace bsg::algos {

class ReplayBufferLog {
 public:
  explicit ReplayBufferLog(std::filesystem::path path) : path_(std::move(path)) {}

  const std::filesystem::path& path() const { return path_; }
  std::int64_t logged_until() const { return logged_until_; }  // transitions [.., logged_until) are on file

  // Appends the held transitions added since the last append (or restore) and fsyncs the file.
  void append(const ReplayBuffer& buffer);
  // Rebuilds `buffer` (empty, of the run's sizes) as it was after `total_added` transitions and cuts
  // later records off the file. Throws CheckpointError naming the file if it is missing, of other
  // sizes, or does not hold the held part of those transitions.
  void restore(ReplayBuffer& buffer, std::int64_t total_added);

 private:
  void rewrite(const ReplayBuffer& buffer);

  std::filesystem::path path_;
  std::int64_t logged_until_ = 0;
  std::int64_t transitions_on_file_ = 0;
};

// replay_buffer.r<rank>.log in `directory`.
std::filesystem::path replay_buffer_log_path(const std::filesystem::path& directory, int rank);

}  // namespace bsg::algos
