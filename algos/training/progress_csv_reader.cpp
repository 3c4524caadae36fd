#include "algos/training/progress_csv_reader.h"

#include <charconv>
#include <cmath>
#include <set>

#include "algos/training/progress_csv_fields.h"
#include "common/message_text.h"

namespace bsg::algos {
namespace {

[[noreturn]] void fail(const std::string& source_name, std::size_t line, const std::string& what) {
  throw ProgressLogError(source_name + ":" + std::to_string(line) + ": " + what);
}

// The value of a field: std::from_chars over the whole field, or nan/inf/-inf
// as format_csv_number writes them.
bool parse_number(const std::string& field, double& value) {
  if (field == "nan") return value = std::nan(""), true;
  if (field == "inf") return value = HUGE_VAL, true;
  if (field == "-inf") return value = -HUGE_VAL, true;
  if (field.empty()) return false;
  const char* end = field.data() + field.size();
  const auto result = std::from_chars(field.data(), end, value);
  return result.ec == std::errc() && result.ptr == end;
}

bool is_column_name(const std::string& name) {
  if (name.empty()) return false;
  for (const char c : name) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
    if (!ok) return false;
  }
  return true;
}

std::size_t column_index(const std::vector<std::string>& columns, const std::string& name) {
  for (std::size_t i = 0; i < columns.size(); ++i) {
    if (columns[i] == name) return i;
  }
  return columns.size();
}

}  // namespace

ProgressLogText read_progress_log(std::string_view text, const std::string& source_name, long long steps_per_epoch) {
  ProgressLogText log;
  std::size_t start = 0;
  std::size_t line_number = 0;
  std::vector<std::string> columns;
  std::size_t epoch_column = 0;
  std::size_t steps_column = 0;
  while (start < text.size()) {
    const std::size_t newline = text.find('\n', start);
    if (newline == std::string_view::npos) {
      log.torn_tail = std::string(text.substr(start));
      break;
    }
    const std::string line(text.substr(start, newline - start));
    start = newline + 1;
    ++line_number;
    const std::vector<std::string> fields = split_csv_line(line);
    if (line_number == 1) {
      std::set<std::string> seen;
      for (const std::string& name : fields) {
        if (!is_column_name(name) || !seen.insert(name).second) {
          fail(source_name, line_number, "not a progress.csv header (column " + printable_excerpt(name, 40) +
                                              " is empty, repeated or not a name): " + printable_excerpt(line));
        }
      }
      columns = fields;
      epoch_column = column_index(columns, "epoch");
      if (columns.empty() || epoch_column != 0) fail(source_name, line_number, "the header's first column is not 'epoch': " + printable_excerpt(line));
      steps_column = column_index(columns, "total_env_steps");
      log.header = line;
      continue;
    }
    if (fields.size() != columns.size()) {
      fail(source_name, line_number, "holds " + std::to_string(fields.size()) + " fields, the header " +
                                         std::to_string(columns.size()) + ": " + printable_excerpt(line));
    }
    std::vector<double> values(fields.size());
    for (std::size_t i = 0; i < fields.size(); ++i) {
      if (!parse_number(fields[i], values[i])) {
        fail(source_name, line_number, "column " + columns[i] + " holds " + printable_excerpt(fields[i], 40) +
                                           ", not a number");
      }
    }
    const double expected_epoch = static_cast<double>(log.rows.size());
    // The writer prints an epoch as an integer (format_csv_number): "00" or
    // "0.0" is the same number but not a row it wrote.
    if (values[epoch_column] != expected_epoch || fields[epoch_column] != format_csv_number(expected_epoch)) {
      fail(source_name, line_number, "epoch " + printable_excerpt(fields[epoch_column], 40) + " where epoch " +
                                         format_csv_number(expected_epoch) +
                                         " belongs (rows must hold epochs 0, 1, 2, ... in order)");
    }
    if (steps_per_epoch > 0 && steps_column < columns.size()) {
      const double expected_steps = (expected_epoch + 1.0) * static_cast<double>(steps_per_epoch);
      if (values[steps_column] != expected_steps) {
        fail(source_name, line_number, "total_env_steps " + printable_excerpt(fields[steps_column], 40) + " where this run's " +
                                           std::to_string(steps_per_epoch) + " steps per epoch give " +
                                           format_csv_number(expected_steps));
      }
    }
    log.rows.push_back(line);
  }
  return log;
}

std::string progress_log_text(const ProgressLogText& log, std::size_t rows) {
  if (log.header.empty()) return {};
  std::string text = log.header + "\n";
  for (std::size_t i = 0; i < rows && i < log.rows.size(); ++i) text += log.rows[i] + "\n";
  return text;
}

}  // namespace bsg::algos
