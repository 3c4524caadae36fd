#include "experiments/progress_columns.h"

#include <algorithm>
#include <cstdlib>
#include <stdexcept>

#include "algos/training/progress_csv_reader.h"
#include "common/csv_text.h"
#include "common/file_reading.h"

namespace bsg::experiments {

std::size_t ProgressColumns::epochs() const {
  return columns.empty() ? 0 : columns.front().size();
}

bool ProgressColumns::has(const std::string& name) const {
  return std::find(names.begin(), names.end(), name) != names.end();
}

const std::vector<double>& ProgressColumns::column(const std::string& name) const {
  const auto found = std::find(names.begin(), names.end(), name);
  if (found == names.end()) throw std::runtime_error(source.string() + ": no column " + name + " in its header");
  return columns[static_cast<std::size_t>(found - names.begin())];
}

ProgressColumns read_progress_columns(const std::filesystem::path& progress_csv) {
  const std::string text = read_regular_file(progress_csv, "progress log");
  const algos::ProgressLogText log = algos::read_progress_log(text, progress_csv.string(), 0);  // checks every line
  ProgressColumns result;
  result.source = progress_csv;
  if (log.header.empty()) throw std::runtime_error(progress_csv.string() + ": empty file (no header)");
  result.names = parse_csv_fields(log.header);
  result.columns.assign(result.names.size(), {});
  for (const std::string& row : log.rows) {
    const std::vector<std::string> fields = parse_csv_fields(row);
    for (std::size_t i = 0; i < fields.size() && i < result.columns.size(); ++i) {
      result.columns[i].push_back(std::strtod(fields[i].c_str(), nullptr));  // numbers: checked by the reader
    }
  }
  return result;
}

}  // namespace bsg::experiments
