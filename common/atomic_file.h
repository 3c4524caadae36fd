// Writing a file so that readers see either the old or the new contents, never
// a mix: write a temporary file beside the target, fsync it, rename it over the
// target, fsync the directory. A process killed at any point (even SIGKILL)
// leaves the previous file intact; at worst a stale temporary is left behind.
// Every write has its own temporary, <target>.tmp.<pid>.<6 random characters>
// (mkostemp), so that two processes writing the same file at once (two
// sweeps, a sweep and `bsg sweep --status`) never share one: the last rename
// wins and neither fails.
#pragma once

#include <filesystem>
#include <string_view>

namespace bsg {

// Throws std::runtime_error naming `path` (and the system error) on failure;
// the target is then unchanged.
void write_file_atomically(const std::filesystem::path& path, std::string_view contents);

// The start of the temporary file names used for `path` (path + ".tmp.").
std::filesystem::path atomic_temporary_prefix(const std::filesystem::path& path);

}  // namespace bsg
