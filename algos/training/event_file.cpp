#include "algos/training/event_file.h"

#include <unistd.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <system_error>

#include "algos/training/progress_csv_fields.h"
#include "algos/training/progress_csv_reader.h"
#include "common/crc32c.h"

namespace bsg::algos {
namespace {

constexpr std::string_view kFilePrefix = "events.out.tfevents.";

double seconds_now() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

// Protocol buffer wire format: a key is (field << 3) | wire type; 0 varint, 1 fixed64,
// 2 length-delimited, 5 fixed32; integers little-endian.
void put_varint(std::string& out, std::uint64_t value) {
  while (value >= 0x80) {
    out.push_back(static_cast<char>((value & 0x7F) | 0x80));
    value >>= 7;
  }
  out.push_back(static_cast<char>(value));
}

template <typename Unsigned>
void put_little_endian(std::string& out, Unsigned value) {
  for (std::size_t i = 0; i < sizeof(Unsigned); ++i) out.push_back(static_cast<char>((value >> (8 * i)) & 0xFF));
}

void put_double(std::string& out, int field, double value) {
  put_varint(out, static_cast<std::uint64_t>(field) << 3 | 1);
  std::uint64_t bits = 0;
  std::memcpy(&bits, &value, sizeof(bits));
  put_little_endian(out, bits);
}

void put_float(std::string& out, int field, float value) {
  put_varint(out, static_cast<std::uint64_t>(field) << 3 | 5);
  std::uint32_t bits = 0;
  std::memcpy(&bits, &value, sizeof(bits));
  put_little_endian(out, bits);
}

void put_bytes(std::string& out, int field, std::string_view bytes) {
  put_varint(out, static_cast<std::uint64_t>(field) << 3 | 2);
  put_varint(out, bytes.size());
  out.append(bytes);
}

// The start of an Event: wall_time and (when not 0, the field's default) step.
std::string event(double wall_time, std::int64_t step) {
  std::string out;
  put_double(out, 1, wall_time);
  if (step != 0) {
    put_varint(out, 2 << 3 | 0);
    put_varint(out, static_cast<std::uint64_t>(step));
  }
  return out;
}

std::string summary_of(const std::vector<NamedScalar>& scalars) {
  std::string summary;
  for (const NamedScalar& scalar : scalars) {
    std::string value;
    put_bytes(value, 1, scalar.name);
    put_float(value, 2, static_cast<float>(scalar.value));
    put_bytes(summary, 1, value);
  }
  return summary;
}

std::string host_name() {
  std::array<char, 256> name{};
  if (gethostname(name.data(), name.size() - 1) != 0 || name[0] == '\0') return "localhost";
  return name.data();
}

}  // namespace

EventFile::EventFile(const std::filesystem::path& directory) {
  const double now = seconds_now();
  char seconds[32];
  std::snprintf(seconds, sizeof(seconds), "%010lld", static_cast<long long>(now));
  path_ = directory / (std::string(kFilePrefix) + seconds + "." + host_name());
  out_.open(path_, std::ios::binary | std::ios::trunc);
  if (!out_) throw std::runtime_error("cannot write the TensorBoard event file " + path_.string());
  std::string first = event(now, 0);
  put_bytes(first, 3, "brain.Event:2");
  write_record(first);
}

void EventFile::write_scalars(std::int64_t step, const std::vector<NamedScalar>& scalars) {
  std::string record = event(seconds_now(), step);
  put_bytes(record, 5, summary_of(scalars));
  write_record(record);
}

void EventFile::write_progress_log(std::string_view progress_csv_text) {
  const ProgressLogText log = read_progress_log(progress_csv_text, path_.string(), 0);
  const std::vector<std::string> names = split_csv_line(log.header);
  for (std::size_t epoch = 0; epoch < log.rows.size(); ++epoch) {
    const std::vector<std::string> fields = split_csv_line(log.rows[epoch]);
    std::vector<NamedScalar> row;
    for (std::size_t c = 0; c < names.size() && c < fields.size(); ++c) {
      row.push_back({names[c], std::strtod(fields[c].c_str(), nullptr)});  // "nan", "inf" too
    }
    write_scalars(static_cast<std::int64_t>(epoch), row);
  }
}

// TFRecord: uint64 length, masked CRC-32C of those 8 bytes, the data, masked CRC-32C of the data.
void EventFile::write_record(const std::string& event) {
  std::string framed;
  put_little_endian(framed, static_cast<std::uint64_t>(event.size()));
  put_little_endian(framed, masked_crc32c(framed));
  framed += event;
  put_little_endian(framed, masked_crc32c(event));
  out_.write(framed.data(), static_cast<std::streamsize>(framed.size()));
  out_.flush();
  if (!out_) throw std::runtime_error("cannot write the TensorBoard event file " + path_.string());
}

void remove_event_files(const std::filesystem::path& directory) {
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator(directory, error)) {
    if (entry.path().filename().string().rfind(kFilePrefix, 0) == 0) std::filesystem::remove(entry.path(), error);
  }
}

}  // namespace bsg::algos
