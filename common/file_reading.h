// Reading a whole file that must be a regular file. A directory, a FIFO (whose
// open would block), a socket or a device in its place is named as what it
// is, not reported as "missing" or read forever.
#pragma once

#include <filesystem>
#include <string>

namespace bsg {

// "a regular file", "missing", "a directory", "a FIFO", "a socket", "a character device",
// "a block device", "a symbolic link to nothing" or "of an unknown kind".
std::string file_kind(const std::filesystem::path& path);

// The bytes of `path`. Throws std::runtime_error "<what> <path> is a directory,
// not a file" (or missing, a FIFO, ...) or "<what> <path> cannot be read: <system error>".
std::string read_regular_file(const std::filesystem::path& path, const std::string& what);

}  // namespace bsg
