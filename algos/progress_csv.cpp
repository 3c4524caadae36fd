#include "algos/progress_csv.h"

#include <charconv>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "common/atomic_file.h"

namespace bsg {
namespace {

std::string header_of(const std::vector<NamedScalar>& row) {
  std::string header;
  for (std::size_t i = 0; i < row.size(); ++i) {
    if (i > 0) header += ',';
    header += row[i].name;
  }
  return header;
}

}  // namespace

std::string format_csv_number(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char text[64];
  const auto result = std::to_chars(text, text + sizeof(text), value);
  return std::string(text, result.ptr);
}

std::vector<std::string> split_csv_line(const std::string& line) {
  std::vector<std::string> fields;
  std::string field;
  std::istringstream stream(line);
  while (std::getline(stream, field, ',')) fields.push_back(field);
  if (!line.empty() && line.back() == ',') fields.emplace_back();
  return fields;
}

ProgressCsv::ProgressCsv(std::filesystem::path path, std::string header)
    : path_(std::move(path)), header_(std::move(header)), file_(path_, std::ios::app) {
  if (!file_) throw std::runtime_error("cannot open " + path_.string() + " for writing");
}

ProgressCsv ProgressCsv::create(const std::filesystem::path& path) {
  {
    std::ofstream truncate(path, std::ios::trunc);
    if (!truncate) throw std::runtime_error("cannot create " + path.string());
  }
  return ProgressCsv(path, "");
}

ProgressCsv ProgressCsv::resume(const std::filesystem::path& path, long long rows_to_keep) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path.string() + " (needed to resume the run)");
  std::string header;
  std::string kept;
  std::string line;
  long long rows = 0;
  if (std::getline(in, line)) header = line;
  while (rows < rows_to_keep && std::getline(in, line)) {
    kept += line;
    kept += '\n';
    ++rows;
  }
  if (rows < rows_to_keep || (rows_to_keep > 0 && header.empty())) {
    throw std::runtime_error(path.string() + " holds " + std::to_string(rows) + " epoch rows, the checkpoint covers " +
                             std::to_string(rows_to_keep) + ": the progress log does not belong to this checkpoint");
  }
  in.close();
  write_file_atomically(path, header.empty() ? std::string() : header + "\n" + kept);
  return ProgressCsv(path, header);
}

void ProgressCsv::write_row(const std::vector<NamedScalar>& row) {
  const std::string header = header_of(row);
  if (header_.empty()) {
    header_ = header;
    file_ << header_ << '\n';
  } else if (header != header_) {
    throw std::logic_error(path_.string() + ": the columns of this epoch (" + header +
                           ") differ from the file's header (" + header_ + ")");
  }
  for (std::size_t i = 0; i < row.size(); ++i) {
    if (i > 0) file_ << ',';
    file_ << format_csv_number(row[i].value);
  }
  file_ << '\n';
  file_.flush();
  if (!file_) throw std::runtime_error("cannot write to " + path_.string());
}

}  // namespace bsg
