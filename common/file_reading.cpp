#include "common/file_reading.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace bsg {
namespace {

std::string kind_of_mode(mode_t mode) {
  if (S_ISREG(mode)) return "a regular file";
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISSOCK(mode)) return "a socket";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  return "of an unknown kind";
}

[[noreturn]] void fail(const std::filesystem::path& path, const std::string& what, const std::string& why) {
  throw std::runtime_error(what + " " + path.string() + " " + why);
}

}  // namespace

std::string file_kind(const std::filesystem::path& path) {
  struct stat info {};
  if (::stat(path.c_str(), &info) == 0) return kind_of_mode(info.st_mode);
  if (::lstat(path.c_str(), &info) == 0 && S_ISLNK(info.st_mode)) return "a symbolic link to nothing";
  return "missing";
}

std::string read_regular_file(const std::filesystem::path& path, const std::string& what) {
  // O_NONBLOCK: opening a FIFO must not wait for a writer; fstat then tells what was opened.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    const int error = errno;
    const std::string kind = file_kind(path);
    if (kind == "missing" || kind == "a symbolic link to nothing") fail(path, what, "is " + kind);
    fail(path, what, "(" + kind + ") cannot be opened: " + std::strerror(error));
  }
  struct stat info {};
  if (::fstat(fd, &info) != 0 || !S_ISREG(info.st_mode)) {
    const std::string kind = ::fstat(fd, &info) == 0 ? kind_of_mode(info.st_mode) : "of an unknown kind";
    ::close(fd);
    fail(path, what, "is " + kind + ", not a file");
  }
  std::string bytes;
  char chunk[65536];
  while (true) {
    const ssize_t n = ::read(fd, chunk, sizeof chunk);
    if (n == 0) break;
    if (n < 0) {
      if (errno == EINTR || errno == EAGAIN) continue;
      const int error = errno;
      ::close(fd);
      fail(path, what, "cannot be read: " + std::string(std::strerror(error)));
    }
    bytes.append(chunk, static_cast<std::size_t>(n));
  }
  ::close(fd);
  return bytes;
}

}  // namespace bsg
