// Reading a run's progress.csv in CLI tests: how many epochs it logs, and its
// rows without the timing columns (time_*, fps), which are the only columns
// allowed to differ between a resumed run and an uninterrupted one.
#pragma once

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "common/csv_text.h"

namespace bsg::testing {

inline int progress_rows(const std::filesystem::path& progress) {
  std::ifstream file(progress);
  std::string line;
  int rows = -1;  // the header
  while (std::getline(file, line)) rows += line.empty() ? 0 : 1;
  return std::max(rows, 0);
}

inline std::vector<std::vector<std::string>> progress_without_timings(const std::filesystem::path& progress) {
  std::vector<std::vector<std::string>> rows;
  std::ifstream file(progress);
  std::string line;
  std::vector<bool> keep;
  while (std::getline(file, line)) {
    const std::vector<std::string> fields = parse_csv_fields(line);
    if (keep.empty()) {
      for (const std::string& name : fields) keep.push_back(name.rfind("time_", 0) != 0 && name != "fps");
    }
    std::vector<std::string> kept;
    for (std::size_t i = 0; i < fields.size(); ++i) {
      if (keep.at(i)) kept.push_back(fields[i]);
    }
    rows.push_back(kept);
  }
  return rows;
}

}  // namespace bsg::testing
