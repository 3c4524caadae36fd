// An exclusive lock on a run directory: flock() on <run dir>/train.lock. The
// sweep takes it before starting `bsg train` there and hands it to the child,
// which holds it for its whole life - also if the sweep itself is killed and
// the child runs on - so that a second sweep on the same directory never
// starts the same run twice at once.
//
// The same lock on <sweep dir>/sweep.lock lets one `bsg sweep` at a time use a
// sweep directory. A lock file holds the pid of the process that holds it
// (record_holder), so that whoever finds it taken can say who has it.
#pragma once

#include <sys/types.h>

#include <filesystem>
#include <iosfwd>
#include <optional>
#include <string>

namespace bsg::experiments {

inline constexpr const char* kRunLockName = "train.lock";
inline constexpr const char* kSweepLockName = "sweep.lock";

class RunLock {
 public:
  // nullopt if another process holds the lock; throws std::runtime_error
  // naming the file if it cannot be opened.
  static std::optional<RunLock> try_acquire(const std::filesystem::path& run_dir);
  // The same for any lock file (e.g. <sweep dir>/sweep.lock).
  static std::optional<RunLock> try_acquire_file(const std::filesystem::path& lock_file);

  // Writes `pid` into the lock file as its holder (the sweep itself, or the
  // child it handed the lock to).
  void record_holder(pid_t pid) const;

  RunLock(RunLock&& other) noexcept;
  RunLock& operator=(RunLock&&) = delete;
  RunLock(const RunLock&) = delete;
  ~RunLock();

  // The locked descriptor (close-on-exec); a child that keeps it open after
  // exec keeps the lock when this object closes its copy.
  int fd() const { return fd_; }

 private:
  explicit RunLock(int fd) : fd_(fd) {}
  int fd_ = -1;
};

// The pid recorded in `lock_file`, if any (whether or not it still holds it).
std::optional<long> recorded_lock_holder(const std::filesystem::path& lock_file);

// "pid 1234" or "an unknown process", for messages.
std::string describe_lock_holder(const std::filesystem::path& lock_file);

// The lock of one sweep on `sweep_dir` (created if missing), recording this process as its holder
// (`bsg sweep`, bsg.sweep), with the stale temporaries of writes a killed sweep left behind removed
// and reported to `notes`. Throws std::runtime_error naming the holder if another sweep has it.
RunLock lock_sweep_directory(const std::filesystem::path& sweep_dir, std::ostream& notes);

}  // namespace bsg::experiments
