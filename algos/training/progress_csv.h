// progress.csv of a run directory (docs/algorithms.md#logged-columns): one comma-separated row per
// epoch, written by rank 0. The header is fixed by the first row; every later
// row must have the same columns in the same order. Values are written in the
// shortest form that reads back to the same double (std::to_chars), so two
// runs that compute the same numbers write the same text.
//
// Each row (with the header, for the first) is one write(2) of whole lines on
// a file opened for appending, so a crash leaves whole rows and at most a torn
// last line, which resume trims (algos/training/progress_csv_reader.h).
//
// A resumed run checks every line (progress_csv_reader.h), keeps the header
// and the rows of the epochs its checkpoint covers and drops any later rows
// (epochs run after the last checkpoint by the interrupted process), then
// appends. The checkpoint holds the text of its epochs' rows
// (training_checkpoint.h): a row that differs from it is an error (the log
// belongs to another run), rows lost or torn within those epochs are restored
// from it.
#pragma once

#include <filesystem>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "algos/core/algorithm.h"
#include "algos/training/progress_csv_fields.h"

namespace bsg::algos {

// What a resume knows from the checkpoint.
struct ProgressResume {
  long long epochs_completed = 0;
  // The progress.csv text of epochs 0 .. epochs_completed - 1 as the
  // checkpoint recorded it (none in checkpoint format 1).
  std::optional<std::string> checkpoint_log;
  long long steps_per_epoch = 0;   // B of the run: total_env_steps = (epoch + 1) B
  std::ostream* notes = nullptr;   // where trimmed, dropped and restored rows are reported
};

class ProgressCsv {
 public:
  // Starts a new, empty file at `path` (overwriting).
  static ProgressCsv create(const std::filesystem::path& path);
  // Checks every line of `path` and keeps the header and the rows of the
  // checkpointed epochs (restoring lost ones from resume.checkpoint_log).
  // Throws ProgressLogError naming the file and line of a row that is
  // malformed or not this run's, std::runtime_error if rows are missing and
  // the checkpoint cannot restore them.
  static ProgressCsv resume(const std::filesystem::path& path, const ProgressResume& resume);

  ProgressCsv(ProgressCsv&& other) noexcept;
  ProgressCsv& operator=(ProgressCsv&&) = delete;
  ProgressCsv(const ProgressCsv&) = delete;
  ~ProgressCsv();

  // Appends one row (the header first if the file has none) in one write.
  // Throws std::logic_error if the columns differ from the header's.
  void write_row(const std::vector<NamedScalar>& row);

  const std::filesystem::path& path() const { return path_; }
  // Everything written so far: header and rows, each line with its newline.
  const std::string& contents() const { return contents_; }

 private:
  ProgressCsv(std::filesystem::path path, std::string header, std::string contents);
  std::filesystem::path path_;
  std::string header_;    // "" until the first row is written
  std::string contents_;  // the file's text
  int fd_ = -1;           // O_APPEND
};

}  // namespace bsg::algos
