// The fields of progress.csv as its writer (progress_csv.h) and its reader
// (progress_csv_reader.h) both spell them.
#pragma once

#include <string>
#include <vector>

namespace bsg::algos {

// The shortest decimal text of `value` that reads back exactly ("nan", "inf" for non-finite values).
std::string format_csv_number(double value);

// Splits a CSV line at commas (no quoting: names and numbers only).
std::vector<std::string> split_csv_line(const std::string& line);

}  // namespace bsg::algos
