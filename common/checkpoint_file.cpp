#include "common/checkpoint_file.h"

#include "common/atomic_file.h"
#include "common/file_reading.h"

namespace bsg {
namespace {

[[noreturn]] void fail(const std::string& source_name, const std::string& what) {
  throw CheckpointError("checkpoint " + source_name + ": " + what);
}

}  // namespace

std::uint64_t fnv1a64(std::string_view bytes) {
  std::uint64_t hash = 0xcbf29ce484222325ULL;  // offset basis
  for (const char byte : bytes) {
    hash ^= static_cast<unsigned char>(byte);
    hash *= 0x100000001b3ULL;  // FNV prime
  }
  return hash;
}

std::string encode_checkpoint_file(std::string_view payload) {
  BinaryWriter writer;
  writer.write_u32(kCheckpointFormatVersion);
  writer.write_u64(payload.size());
  std::string file(kCheckpointMagic);
  file += writer.bytes();
  file += payload;
  BinaryWriter checksum;
  checksum.write_u64(fnv1a64(payload));
  file += checksum.bytes();
  return file;
}

std::string decode_checkpoint_file(std::string_view file_bytes, const std::string& source_name) {
  return decode_checkpoint_contents(file_bytes, source_name).payload;
}

CheckpointContents decode_checkpoint_contents(std::string_view file_bytes, const std::string& source_name) {
  if (file_bytes.size() < kCheckpointMagic.size() || file_bytes.substr(0, kCheckpointMagic.size()) != kCheckpointMagic) {
    fail(source_name, "not a bsg checkpoint (bad magic header)");
  }
  BinaryReader header(file_bytes.substr(kCheckpointMagic.size()), source_name);
  const std::uint32_t version = header.read_u32("format version");
  if (version < kOldestCheckpointFormatVersion || version > kCheckpointFormatVersion) {
    fail(source_name, "format version " + std::to_string(version) + " is not supported (this bsg reads versions " +
         std::to_string(kOldestCheckpointFormatVersion) + " to " + std::to_string(kCheckpointFormatVersion) + ")");
  }
  const std::uint64_t payload_size = header.read_u64("payload size");
  const std::size_t header_size = kCheckpointMagic.size() + 4 + 8;
  const std::size_t available = file_bytes.size() - header_size;
  if (available < 8 || payload_size != available - 8) {
    fail(source_name, "truncated or corrupt: header announces " + std::to_string(payload_size) + " payload bytes plus an " +
         "8-byte checksum, the file holds " + std::to_string(available) + " bytes after the header");
  }
  const std::string_view payload = file_bytes.substr(header_size, payload_size);
  BinaryReader trailer(file_bytes.substr(header_size + payload_size), source_name);
  const std::uint64_t stored_checksum = trailer.read_u64("checksum");
  if (stored_checksum != fnv1a64(payload)) fail(source_name, "corrupt: checksum mismatch");
  return CheckpointContents{version, std::string(payload)};
}

void write_checkpoint_file(const std::filesystem::path& path, std::string_view payload) {
  write_file_atomically(path, encode_checkpoint_file(payload));
}

std::string read_checkpoint_file(const std::filesystem::path& path) { return read_checkpoint_contents(path).payload; }

CheckpointContents read_checkpoint_contents(const std::filesystem::path& path) {
  std::string bytes;
  try {
    bytes = read_regular_file(path, "checkpoint");
  } catch (const std::runtime_error& e) {
    throw CheckpointError(e.what());
  }
  return decode_checkpoint_contents(bytes, path.string());
}

}  // namespace bsg
