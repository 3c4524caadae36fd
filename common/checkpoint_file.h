// The checkpoint container: a versioned binary file around an opaque payload
// (the payload's layout belongs to whoever writes it, e.g. algos/training/training_checkpoint.h).
//
// Layout (all integers little-endian):
//   magic         8 bytes  "BSGCKPT\n"
//   version       u32      kCheckpointFormatVersion
//   payload size  u64      bytes
//   payload       ...
//   checksum      u64      FNV-1a 64 of the payload
//
// Writes are atomic (atomic_file.h). Reading checks magic, version, size and
// checksum and throws CheckpointError naming the file on any mismatch, so a
// truncated, corrupt or foreign file is reported, never loaded.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

#include "common/binary_io.h"

namespace bsg {

inline constexpr std::string_view kCheckpointMagic{"BSGCKPT\n", 8};
// Version 2 added the progress log to the training checkpoint's payload
// (algos/training/training_checkpoint.h); version 1 files are still read.
inline constexpr std::uint32_t kCheckpointFormatVersion = 2;
inline constexpr std::uint32_t kOldestCheckpointFormatVersion = 1;

// FNV-1a, 64 bit.
std::uint64_t fnv1a64(std::string_view bytes);

// The whole file image (header, payload, checksum) for `payload`.
std::string encode_checkpoint_file(std::string_view payload);
// The payload of a file image; `source_name` names the file in errors.
std::string decode_checkpoint_file(std::string_view file_bytes, const std::string& source_name);

// The payload and the format version it was written in.
struct CheckpointContents {
  std::uint32_t format_version = 0;
  std::string payload;
};
CheckpointContents decode_checkpoint_contents(std::string_view file_bytes, const std::string& source_name);

// Atomic write of encode_checkpoint_file(payload) to `path`.
void write_checkpoint_file(const std::filesystem::path& path, std::string_view payload);
// Reads and checks `path`; returns the payload. Throws CheckpointError naming
// the path (and what it is if it is not a regular file: a directory, a FIFO).
std::string read_checkpoint_file(const std::filesystem::path& path);
CheckpointContents read_checkpoint_contents(const std::filesystem::path& path);

}  // namespace bsg
