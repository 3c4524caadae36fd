// Writing a file so that readers see either the old or the new contents, never
// a mix: write a temporary file beside the target, fsync it, rename it over the
// target, fsync the directory. A process killed at any point (even SIGKILL)
// leaves the previous file intact; at worst a stale temporary is left behind.
// Every write has its own temporary, <target>.tmp.<pid>.<6 random characters>
// (mkostemp), so that two processes writing the same file at once (two
// sweeps, a sweep and `bsg sweep --status`) never share one: the last rename
// wins and neither fails.
#pragma once

#include <chrono>
#include <filesystem>
#include <string_view>
#include <vector>

namespace bsg {

// Throws std::runtime_error naming `path` (and the system error) on failure;
// the target is then unchanged.
void write_file_atomically(const std::filesystem::path& path, std::string_view contents);

// The start of the temporary file names used for `path` (path + ".tmp.").
std::filesystem::path atomic_temporary_prefix(const std::filesystem::path& path);

// When a temporary left in a directory can no longer be part of a write in
// progress. A write lasts milliseconds, so a temporary is stale once its
// writer is gone from this host and it has not been touched for
// `dead_writer_age`, or, whoever wrote it (another host on a shared file
// system, or a reused pid), once it is older than `any_writer_age`.
struct StaleTemporaryAges {
  std::chrono::seconds dead_writer_age{60};
  std::chrono::seconds any_writer_age{24 * 3600};
};

// Removes the stale temporaries (<name>.tmp.<pid>.<6 characters>) directly in
// `directory` and returns their paths; other files, and temporaries a write
// may still be using, are left alone. A missing directory has none.
std::vector<std::filesystem::path> remove_stale_temporaries(const std::filesystem::path& directory,
                                                           StaleTemporaryAges ages = {});

}  // namespace bsg
