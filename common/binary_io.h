// Little-endian binary encoding for checkpoint payloads (checkpoint_file.h).
// Every value is written with a fixed width and byte order, independent of the
// host, so a checkpoint is portable. The reader checks every read against the
// end of the data and throws CheckpointError naming the source (the file) and
// the field it was reading, so a truncated or corrupt file never yields
// garbage silently.
//
// Named sections (write_section / expect_section) mark the start of each part
// of a payload, so a reader that gets out of step reports which part it
// expected and what it found.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>

#include "common/message_text.h"

namespace bsg {

// A checkpoint that cannot be written, read or understood. The message names
// the file and what was wrong.
class CheckpointError : public std::runtime_error {
 public:
  // Made printable and bounded (message_text.h): it may quote the file's bytes.
  explicit CheckpointError(const std::string& message) : std::runtime_error(printable_message(message)) {}
};

class BinaryWriter {
 public:
  void write_u32(std::uint32_t value);
  void write_u64(std::uint64_t value);
  void write_i64(std::int64_t value);
  void write_f64(double value);
  void write_bool(bool value);
  // Length (u64) followed by the bytes.
  void write_string(std::string_view text);
  // Length (u64) followed by the values.
  void write_vector(const Eigen::Ref<const Eigen::VectorXd>& values);
  // A section marker: the string "section" then the name.
  void write_section(std::string_view name);

  const std::string& bytes() const { return bytes_; }

 private:
  void append_le(std::uint64_t value, int num_bytes);
  std::string bytes_;
};

class BinaryReader {
 public:
  // `source_name` (e.g. the file path) appears in every error message.
  BinaryReader(std::string_view bytes, std::string source_name);

  std::uint32_t read_u32(std::string_view field);
  std::uint64_t read_u64(std::string_view field);
  std::int64_t read_i64(std::string_view field);
  double read_f64(std::string_view field);
  bool read_bool(std::string_view field);
  std::string read_string(std::string_view field);
  Eigen::VectorXd read_vector(std::string_view field);
  // read_vector that also checks the length.
  Eigen::VectorXd read_vector(std::string_view field, Eigen::Index expected_size);
  // Throws unless the next item is the section marker `name`.
  void expect_section(std::string_view name);
  // Throws unless every byte has been read.
  void expect_end() const;

  std::size_t remaining() const { return bytes_.size() - position_; }
  const std::string& source_name() const { return source_name_; }
  // A CheckpointError naming the source, e.g. fail("policy parameters: size 3, expected 4").
  [[noreturn]] void fail(const std::string& what) const;

 private:
  std::uint64_t read_le(int num_bytes, std::string_view field);
  std::string_view bytes_;
  std::string source_name_;
  std::size_t position_ = 0;
};

}  // namespace bsg
