#include "common/binary_io.h"

#include <bit>
#include <utility>

namespace bsg {

void BinaryWriter::append_le(std::uint64_t value, int num_bytes) {
  for (int i = 0; i < num_bytes; ++i) bytes_.push_back(static_cast<char>((value >> (8 * i)) & 0xffU));
}

void BinaryWriter::write_u32(std::uint32_t value) { append_le(value, 4); }
void BinaryWriter::write_u64(std::uint64_t value) { append_le(value, 8); }
void BinaryWriter::write_i64(std::int64_t value) { append_le(static_cast<std::uint64_t>(value), 8); }
void BinaryWriter::write_f64(double value) { append_le(std::bit_cast<std::uint64_t>(value), 8); }
void BinaryWriter::write_bool(bool value) { append_le(value ? 1U : 0U, 1); }

void BinaryWriter::write_string(std::string_view text) {
  write_u64(text.size());
  bytes_.append(text);
}

void BinaryWriter::write_vector(const Eigen::Ref<const Eigen::VectorXd>& values) {
  write_u64(static_cast<std::uint64_t>(values.size()));
  for (Eigen::Index i = 0; i < values.size(); ++i) write_f64(values[i]);
}

void BinaryWriter::write_section(std::string_view name) {
  write_string("section");
  write_string(name);
}

BinaryReader::BinaryReader(std::string_view bytes, std::string source_name)
    : bytes_(bytes), source_name_(std::move(source_name)) {}

void BinaryReader::fail(const std::string& what) const {
  throw CheckpointError("checkpoint " + source_name_ + ": " + what);
}

std::uint64_t BinaryReader::read_le(int num_bytes, std::string_view field) {
  if (remaining() < static_cast<std::size_t>(num_bytes)) {
    fail("truncated while reading " + std::string(field) + " (needs " + std::to_string(num_bytes) +
         " bytes at offset " + std::to_string(position_) + ", " + std::to_string(remaining()) + " left)");
  }
  std::uint64_t value = 0;
  for (int i = 0; i < num_bytes; ++i) {
    value |= static_cast<std::uint64_t>(static_cast<unsigned char>(bytes_[position_ + i])) << (8 * i);
  }
  position_ += static_cast<std::size_t>(num_bytes);
  return value;
}

std::uint32_t BinaryReader::read_u32(std::string_view field) {
  return static_cast<std::uint32_t>(read_le(4, field));
}
std::uint64_t BinaryReader::read_u64(std::string_view field) { return read_le(8, field); }
std::int64_t BinaryReader::read_i64(std::string_view field) { return static_cast<std::int64_t>(read_le(8, field)); }
double BinaryReader::read_f64(std::string_view field) { return std::bit_cast<double>(read_le(8, field)); }

bool BinaryReader::read_bool(std::string_view field) {
  const std::uint64_t value = read_le(1, field);
  if (value > 1) fail(std::string(field) + ": invalid boolean byte " + std::to_string(value));
  return value == 1;
}

std::string BinaryReader::read_string(std::string_view field) {
  const std::uint64_t size = read_u64(field);
  if (size > remaining()) {
    fail("truncated or corrupt: " + std::string(field) + " claims " + std::to_string(size) + " bytes, " +
         std::to_string(remaining()) + " left");
  }
  std::string text(bytes_.substr(position_, size));
  position_ += size;
  return text;
}

Eigen::VectorXd BinaryReader::read_vector(std::string_view field) {
  const std::uint64_t size = read_u64(field);
  if (size > remaining() / 8) {
    fail("truncated or corrupt: " + std::string(field) + " claims " + std::to_string(size) + " values, " +
         std::to_string(remaining()) + " bytes left");
  }
  Eigen::VectorXd values(static_cast<Eigen::Index>(size));
  for (Eigen::Index i = 0; i < values.size(); ++i) values[i] = read_f64(field);
  return values;
}

Eigen::VectorXd BinaryReader::read_vector(std::string_view field, Eigen::Index expected_size) {
  Eigen::VectorXd values = read_vector(field);
  if (values.size() != expected_size) {
    fail(std::string(field) + " has " + std::to_string(values.size()) + " values, expected " +
         std::to_string(expected_size) + " (a checkpoint of a different configuration?)");
  }
  return values;
}

void BinaryReader::expect_section(std::string_view name) {
  const std::size_t start = position_;
  const std::string marker = read_string("section marker");
  const std::string found = read_string("section name");
  if (marker != "section" || found != name) {
    fail("expected section '" + std::string(name) + "' at offset " + std::to_string(start) + ", found '" +
         (marker == "section" ? found : marker) + "'");
  }
}

void BinaryReader::expect_end() const {
  if (remaining() != 0) fail(std::to_string(remaining()) + " unexpected bytes after the last section");
}

}  // namespace bsg
