#include "common/atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>

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

}  // namespace

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
