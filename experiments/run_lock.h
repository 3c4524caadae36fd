// An exclusive lock on a run directory: flock() on <run dir>/train.lock. The
// sweep takes it before starting `bsg train` there and hands it to the child,
// which holds it for its whole life - also if the sweep itself is killed and
// the child runs on - so that a second sweep on the same directory never
// starts the same run twice at once.
#pragma once

#include <filesystem>
#include <optional>

namespace bsg {

inline constexpr const char* kRunLockName = "train.lock";

class RunLock {
 public:
  // nullopt if another process holds the lock; throws std::runtime_error
  // naming the file if it cannot be opened.
  static std::optional<RunLock> try_acquire(const std::filesystem::path& run_dir);

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

}  // namespace bsg
