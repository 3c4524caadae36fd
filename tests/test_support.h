// Helpers shared by the test folders: a scratch directory that removes itself,
// reading and writing whole files and CSV files, and a substring check. Included as
// "../test_support.h" from tests/<folder>/ (tests/ itself is not an include directory).
#pragma once

#include <gtest/gtest.h>
#include <stdlib.h>  // mkdtemp

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "algos/training/progress_csv.h"

namespace bsg::testing {

// A fresh directory /tmp/bsg_<name>_XXXXXX, removed with everything in it
// when the object goes out of scope.
class TemporaryDirectory {
 public:
  explicit TemporaryDirectory(const std::string& name = "test") {
    std::string pattern = "/tmp/bsg_" + name + "_XXXXXX";
    if (mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("cannot create " + pattern);
    path_ = pattern;
  }
  ~TemporaryDirectory() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  TemporaryDirectory(const TemporaryDirectory&) = delete;
  TemporaryDirectory& operator=(const TemporaryDirectory&) = delete;

  const std::filesystem::path& path() const { return path_; }
  // The path of `name` inside the directory, as a string (for command lines).
  std::string str(const std::string& name) const { return (path_ / name).string(); }

 private:
  std::filesystem::path path_;
};

// The whole file, byte for byte ("" if it cannot be opened).
inline std::string read_text_file(const std::filesystem::path& path) {
  std::ifstream file(path, std::ios::binary);
  std::ostringstream contents;
  contents << file.rdbuf();
  return contents.str();
}

// Replaces the file's contents with `text`, byte for byte.
inline void write_text_file(const std::filesystem::path& path, const std::string& text) {
  std::ofstream file(path, std::ios::binary | std::ios::trunc);
  file << text;
}

// The lines of a CSV file (such as progress.csv) split into fields with
// bsg::algos::split_csv_line; the header is the first row.
inline std::vector<std::vector<std::string>> read_csv_rows(const std::filesystem::path& path) {
  std::ifstream file(path);
  std::vector<std::vector<std::string>> rows;
  std::string line;
  while (std::getline(file, line)) rows.push_back(algos::split_csv_line(line));
  return rows;
}

// The numeric columns of a CSV file with a header (such as progress.csv), by name.
inline std::map<std::string, std::vector<double>> read_csv_columns(const std::filesystem::path& path) {
  const std::vector<std::vector<std::string>> rows = read_csv_rows(path);
  std::map<std::string, std::vector<double>> columns;
  for (std::size_t row = 1; row < rows.size(); ++row) {
    for (std::size_t i = 0; i < rows.front().size() && i < rows[row].size(); ++i) {
      columns[rows.front()[i]].push_back(std::stod(rows[row][i]));
    }
  }
  return columns;
}

// gmock's HasSubstr without gmock: says what was missing from which text.
inline ::testing::AssertionResult contains(const std::string& text, const std::string& part) {
  if (text.find(part) != std::string::npos) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "'" << part << "' not found in:\n" << text;
}

}  // namespace bsg::testing
