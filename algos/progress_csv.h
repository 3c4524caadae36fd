// progress.csv of a run directory (docs/algorithms.md#logged-columns): one comma-separated row per
// epoch, written by rank 0. The header is fixed by the first row; every later
// row must have the same columns in the same order. Values are written in the
// shortest form that reads back to the same double (std::to_chars), so two
// runs that compute the same numbers write the same text.
//
// A resumed run keeps the header and the rows of the epochs its checkpoint
// covers and drops any later rows (epochs run after the last checkpoint by
// the interrupted process), then appends.
#pragma once

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "algos/algorithm.h"

namespace bsg {

class ProgressCsv {
 public:
  // Starts a new, empty file at `path` (overwriting).
  static ProgressCsv create(const std::filesystem::path& path);
  // Keeps the header and the first `rows_to_keep` data rows of `path`; throws
  // std::runtime_error naming the file if it holds fewer rows.
  static ProgressCsv resume(const std::filesystem::path& path, long long rows_to_keep);

  // Appends one row (the header first if the file has none) and flushes.
  // Throws std::logic_error if the columns differ from the header's.
  void write_row(const std::vector<NamedScalar>& row);

  const std::filesystem::path& path() const { return path_; }

 private:
  ProgressCsv(std::filesystem::path path, std::string header);
  std::filesystem::path path_;
  std::string header_;  // "" until the first row is written
  std::ofstream file_;
};

// The shortest decimal text of `value` that reads back exactly ("nan", "inf" for non-finite values).
std::string format_csv_number(double value);

// Splits a CSV line at commas (no quoting: names and numbers only).
std::vector<std::string> split_csv_line(const std::string& line);

}  // namespace bsg
