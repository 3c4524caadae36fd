// libFuzzer target: the progress.csv reader (algos/training/progress_csv_reader.h).
// Any input gives rows that satisfy the reader's promises or a ProgressLogError.
#include <cstddef>
#include <cstdint>
#include <string>

#include "algos/training/progress_csv.h"
#include "algos/training/progress_csv_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const bsg::algos::ProgressLogText log = bsg::algos::read_progress_log(text, "fuzz.csv", 100);
    const std::size_t columns = bsg::algos::split_csv_line(log.header).size();
    for (std::size_t i = 0; i < log.rows.size(); ++i) {
      if (bsg::algos::split_csv_line(log.rows[i]).size() != columns) __builtin_trap();
      if (bsg::algos::split_csv_line(log.rows[i]).front() != std::to_string(i)) __builtin_trap();
    }
  } catch (const bsg::algos::ProgressLogError&) {
  }
  return 0;
}
