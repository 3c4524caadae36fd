// Writing a file so that readers see either the old or the new contents, never
// a mix: write a temporary file beside the target, fsync it, rename it over the
// target, fsync the directory. A process killed at any point (even SIGKILL)
// leaves the previous file intact; at worst a stale temporary is left behind,
// which the next write replaces.
#pragma once

#include <filesystem>
#include <string_view>

namespace bsg {

// Throws std::runtime_error naming `path` (and the system error) on failure;
// the target is then unchanged.
void write_file_atomically(const std::filesystem::path& path, std::string_view contents);

// The temporary file name used for `path` (path + ".tmp").
std::filesystem::path atomic_temporary_path(const std::filesystem::path& path);

}  // namespace bsg
