// A finished or running run's progress.csv (algos/training/progress_csv.h
// writes it) as named columns of numbers, for curves and training-safety
// aggregates. Every complete line is checked as a resume checks it
// (algos/training/progress_csv_reader.h); a torn last line is left out.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace bsg::experiments {

struct ProgressColumns {
  std::filesystem::path source;
  std::vector<std::string> names;            // the header
  std::vector<std::vector<double>> columns;  // one per name, one value per epoch

  std::size_t epochs() const;
  bool has(const std::string& name) const;
  // Throws std::runtime_error naming the file and the column if it is absent.
  const std::vector<double>& column(const std::string& name) const;
};

// Throws std::runtime_error (ProgressLogError) naming the file and line at fault.
ProgressColumns read_progress_columns(const std::filesystem::path& progress_csv);

}  // namespace bsg::experiments
