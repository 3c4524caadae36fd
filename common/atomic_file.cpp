#include "common/atomic_file.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <stdexcept>
#include <string>
#include <system_error>

namespace bsg {
namespace {

[[noreturn]] void fail(const std::filesystem::path& path, const std::string& what, int error) {
  throw std::runtime_error("cannot write " + path.string() + ": " + what + ": " + std::strerror(error));
}

// Closes the descriptor on every path out of write_file_atomically.
class FileDescriptor {
 public:
  explicit FileDescriptor(int fd) : fd_(fd) {}
  ~FileDescriptor() {
    if (fd_ >= 0) ::close(fd_);
  }
  FileDescriptor(const FileDescriptor&) = delete;
  FileDescriptor& operator=(const FileDescriptor&) = delete;
  int get() const { return fd_; }
  int release() {
    const int fd = fd_;
    fd_ = -1;
    return fd;
  }

 private:
  int fd_;
};

// The writer's pid if `name` is a temporary of write_file_atomically:
// <target>.tmp.<pid>.<6 characters of mkostemp>.
std::optional<long> temporary_writer_pid(const std::string& name) {
  const std::size_t marker = name.rfind(".tmp.");
  if (marker == std::string::npos || marker == 0) return std::nullopt;
  const std::size_t pid_start = marker + 5;
  const std::size_t dot = name.find('.', pid_start);
  if (dot == std::string::npos || dot == pid_start || dot - pid_start > 10 || name.size() - dot - 1 != 6) {
    return std::nullopt;
  }
  const std::string pid = name.substr(pid_start, dot - pid_start);
  if (!std::all_of(pid.begin(), pid.end(), [](unsigned char c) { return std::isdigit(c) != 0; })) return std::nullopt;
  return std::stol(pid);
}

bool process_alive_here(long pid) {
  if (pid <= 0) return false;
  return ::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM;  // EPERM: it exists, owned by another user
}

}  // namespace

std::vector<std::filesystem::path> remove_stale_temporaries(const std::filesystem::path& directory,
                                                           StaleTemporaryAges ages) {
  std::vector<std::filesystem::path> removed;
  std::error_code error;
  std::filesystem::directory_iterator entries(directory, error);
  if (error) return removed;  // no directory, no temporaries
  const auto now = std::filesystem::file_time_type::clock::now();
  for (const std::filesystem::directory_entry& entry : entries) {
    const std::optional<long> pid = temporary_writer_pid(entry.path().filename().string());
    if (!pid || !entry.is_regular_file(error)) continue;
    const auto modified = entry.last_write_time(error);
    if (error) continue;  // gone meanwhile
    const auto age = now - modified;
    const bool stale = age >= ages.any_writer_age ||
                       (age >= ages.dead_writer_age && !process_alive_here(*pid));
    if (stale && std::filesystem::remove(entry.path(), error)) removed.push_back(entry.path());
  }
  std::sort(removed.begin(), removed.end());
  return removed;
}

std::filesystem::path atomic_temporary_prefix(const std::filesystem::path& path) {
  std::filesystem::path prefix = path;
  prefix += ".tmp.";
  return prefix;
}

void write_file_atomically(const std::filesystem::path& path, std::string_view contents) {
  std::string name = atomic_temporary_prefix(path).string() + std::to_string(::getpid()) + ".XXXXXX";
  const int fd = ::mkostemp(name.data(), O_CLOEXEC);
  if (fd < 0) fail(path, "cannot create a temporary " + name, errno);
  const std::filesystem::path temporary = name;
  {
    FileDescriptor file(fd);
    ::fchmod(file.get(), 0644);  // as open(0644) under the usual umask; mkostemp makes 0600
    std::size_t written = 0;
    while (written < contents.size()) {
      const ssize_t n = ::write(file.get(), contents.data() + written, contents.size() - written);
      if (n < 0) {
        if (errno == EINTR) continue;
        const int error = errno;
        ::unlink(temporary.c_str());
        fail(path, "writing " + temporary.string(), error);
      }
      written += static_cast<std::size_t>(n);
    }
    if (::fsync(file.get()) != 0) {
      const int error = errno;
      ::unlink(temporary.c_str());
      fail(path, "fsync of " + temporary.string(), error);
    }
    if (::close(file.release()) != 0) {
      const int error = errno;
      ::unlink(temporary.c_str());
      fail(path, "closing " + temporary.string(), error);
    }
  }
  if (::rename(temporary.c_str(), path.c_str()) != 0) {
    const int error = errno;
    ::unlink(temporary.c_str());
    fail(path, "renaming " + temporary.string(), error);
  }
  // Make the rename itself durable.
  const std::filesystem::path directory = path.has_parent_path() ? path.parent_path() : ".";
  FileDescriptor dir(::open(directory.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC));
  if (dir.get() >= 0) ::fsync(dir.get());
}

}  // namespace bsg
