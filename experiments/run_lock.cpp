#include "experiments/run_lock.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <ostream>
#include <stdexcept>
#include <vector>

#include "common/atomic_file.h"

namespace bsg::experiments {

std::optional<RunLock> RunLock::try_acquire(const std::filesystem::path& run_dir) {
  return try_acquire_file(run_dir / kRunLockName);
}

std::optional<RunLock> RunLock::try_acquire_file(const std::filesystem::path& path) {
  const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd < 0) throw std::runtime_error("cannot open lock file " + path.string() + ": " + std::strerror(errno));
  if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
    const int error = errno;
    ::close(fd);
    if (error == EWOULDBLOCK) return std::nullopt;
    throw std::runtime_error("cannot lock " + path.string() + ": " + std::strerror(error));
  }
  return RunLock(fd);
}

void RunLock::record_holder(pid_t pid) const {
  const std::string text = std::to_string(pid) + "\n";
  if (::ftruncate(fd_, 0) == 0) {
    [[maybe_unused]] const ssize_t written = ::pwrite(fd_, text.data(), text.size(), 0);
  }
}

std::optional<long> recorded_lock_holder(const std::filesystem::path& lock_file) {
  std::ifstream file(lock_file);
  long pid = 0;
  if (file >> pid && pid > 0) return pid;
  return std::nullopt;
}

std::string describe_lock_holder(const std::filesystem::path& lock_file) {
  const std::optional<long> pid = recorded_lock_holder(lock_file);
  return pid ? "pid " + std::to_string(*pid) : std::string("an unknown process");
}

RunLock::RunLock(RunLock&& other) noexcept : fd_(other.fd_) { other.fd_ = -1; }

RunLock::~RunLock() {
  if (fd_ >= 0) ::close(fd_);
}

RunLock lock_sweep_directory(const std::filesystem::path& sweep_dir, std::ostream& notes) {
  std::filesystem::create_directories(sweep_dir);
  const std::filesystem::path lock_file = sweep_dir / kSweepLockName;
  std::optional<RunLock> lock = RunLock::try_acquire_file(lock_file);
  if (!lock) {
    throw std::runtime_error("another bsg sweep (" + describe_lock_holder(lock_file) + ") is using " +
                             sweep_dir.string() + " (it holds " + lock_file.string() +
                             "); wait for it to end or choose another --out");
  }
  lock->record_holder(::getpid());
  // A sweep killed during a write of its files leaves the write's temporary behind.
  const std::vector<std::filesystem::path> stale = remove_stale_temporaries(sweep_dir);
  if (!stale.empty()) {
    notes << "bsg sweep: removed " << stale.size() << " stale temporary file" << (stale.size() == 1 ? "" : "s")
          << " left by interrupted writes in " << sweep_dir.string() << "\n";
  }
  return std::move(*lock);
}

}  // namespace bsg::experiments
