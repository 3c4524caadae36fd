#include "algos/training/replay_buffer_log.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <string>
#include <string_view>

#include "common/atomic_file.h"
#include "common/binary_io.h"
#include "common/checkpoint_file.h"
#include "common/file_reading.h"

namespace bsg::algos {
namespace {

constexpr std::string_view kMagic = "BSGRBLOG";
constexpr std::uint32_t kFormat = 1;
constexpr std::size_t kHeaderBytes = 16;
constexpr std::size_t kRecordHeaderBytes = 24;

void put_le(std::string& out, std::uint64_t value, int bytes) {
  for (int i = 0; i < bytes; ++i) out.push_back(static_cast<char>((value >> (8 * i)) & 0xff));
}

std::uint64_t get_le(std::string_view in, std::size_t at, int bytes) {
  std::uint64_t value = 0;
  for (int i = 0; i < bytes; ++i) value |= static_cast<std::uint64_t>(static_cast<unsigned char>(in[at + i])) << (8 * i);
  return value;
}

std::string header(const ReplayBuffer& buffer) {
  std::string out(kMagic);
  put_le(out, kFormat, 4);
  put_le(out, static_cast<std::uint64_t>(ReplayBuffer::bytes_per_transition(
                  buffer.observation_size(), buffer.action_size(), buffer.cost_count())),
         4);
  return out;
}

std::string record(const ReplayBuffer& buffer, std::int64_t first, std::int64_t count) {
  std::string payload;
  buffer.write_transitions(first, count, payload);
  std::string out;
  put_le(out, static_cast<std::uint64_t>(first), 8);
  put_le(out, static_cast<std::uint64_t>(count), 8);
  put_le(out, fnv1a64(payload), 8);
  out += payload;
  return out;
}

[[noreturn]] void fail(const std::filesystem::path& path, const std::string& what) {
  throw CheckpointError(path.string() + ": " + what);
}

}  // namespace

std::filesystem::path replay_buffer_log_path(const std::filesystem::path& directory, int rank) {
  return directory / ("replay_buffer.r" + std::to_string(rank) + ".log");
}

void ReplayBufferLog::rewrite(const ReplayBuffer& buffer) {
  const std::int64_t total = buffer.total_added();
  write_file_atomically(path_, header(buffer) + record(buffer, total - buffer.size(), buffer.size()));
  logged_until_ = total;
  transitions_on_file_ = buffer.size();
}

void ReplayBufferLog::append(const ReplayBuffer& buffer) {
  const std::int64_t total = buffer.total_added();
  // Transitions overwritten since the last append are not needed: the held ones follow on.
  const std::int64_t first = std::max(logged_until_, total - buffer.size());
  if (!std::filesystem::exists(path_) || transitions_on_file_ + (total - first) > 2 * buffer.capacity()) {
    rewrite(buffer);  // a new record, or one that would hold more than twice the capacity
    return;
  }
  if (total == logged_until_) return;
  const std::string bytes = record(buffer, first, total - first);
  const int fd = ::open(path_.c_str(), O_WRONLY | O_APPEND | O_CLOEXEC);
  if (fd < 0) fail(path_, std::string("cannot open for appending: ") + std::strerror(errno));
  std::size_t written = 0;
  while (written < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + written, bytes.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int error = errno;
      ::close(fd);
      fail(path_, std::string("cannot append: ") + std::strerror(error));
    }
    written += static_cast<std::size_t>(n);
  }
  if (::fsync(fd) != 0 || ::close(fd) != 0) fail(path_, std::string("cannot sync: ") + std::strerror(errno));
  transitions_on_file_ += total - first;
  logged_until_ = total;
}

void ReplayBufferLog::restore(ReplayBuffer& buffer, std::int64_t total_added) {
  const std::string text = read_regular_file(path_, "replay buffer record");
  const std::string expected_header = header(buffer);
  if (text.size() < kHeaderBytes || text.compare(0, kHeaderBytes, expected_header) != 0) {
    fail(path_, "not a replay buffer record of this run's sizes (format, bytes per transition)");
  }
  const std::int64_t row_bytes =
      ReplayBuffer::bytes_per_transition(buffer.observation_size(), buffer.action_size(), buffer.cost_count());
  const std::int64_t needed_from = std::max<std::int64_t>(0, total_added - buffer.capacity());
  std::int64_t covered_until = needed_from;
  std::int64_t on_file = 0;
  std::size_t at = kHeaderBytes;
  while (at + kRecordHeaderBytes <= text.size()) {
    const std::int64_t first = static_cast<std::int64_t>(get_le(text, at, 8));
    const std::int64_t count = static_cast<std::int64_t>(get_le(text, at + 8, 8));
    const std::uint64_t checksum = get_le(text, at + 16, 8);
    const std::size_t payload_at = at + kRecordHeaderBytes;
    if (count < 0 || first < 0 || first + count > total_added ||
        static_cast<std::uint64_t>(count) * static_cast<std::uint64_t>(row_bytes) > text.size() - payload_at) {
      break;  // after the checkpoint, or torn
    }
    const std::string_view payload(text.data() + payload_at, static_cast<std::size_t>(count * row_bytes));
    if (fnv1a64(payload) != checksum) break;  // torn
    const std::int64_t end = first + count;
    if (end > needed_from) {
      if (first > covered_until) fail(path_, "transitions " + std::to_string(covered_until) + " to " +
                                                 std::to_string(first) + " are missing");
      const std::int64_t from = std::max(first, needed_from);
      buffer.restore_transitions(from, end - from, payload.substr(static_cast<std::size_t>((from - first) * row_bytes)));
      covered_until = std::max(covered_until, end);
    }
    on_file += count;
    at = payload_at + payload.size();
  }
  if (covered_until != total_added) {
    fail(path_, "holds transitions up to " + std::to_string(covered_until) + ", the checkpoint needs " +
                    std::to_string(total_added));
  }
  buffer.restore_counters(total_added);
  if (at != text.size()) std::filesystem::resize_file(path_, at);  // drop what came after the checkpoint
  logged_until_ = total_added;
  transitions_on_file_ = on_file;
}

}  // namespace bsg::algos
