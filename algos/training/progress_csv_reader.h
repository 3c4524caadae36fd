// Reading progress.csv back (algos/training/progress_csv.h writes it): the checks a
// resumed run applies to every line before it appends to the file.
//
// A line is a complete row only with its newline: the writer emits each row
// (with the header, for the first) in one write(2) ending in '\n', so text
// after the last newline is what a crash during a write left - a torn tail,
// reported separately and never taken as a row. Every complete line must
// hold: the header's field count, a number in each field ("nan", "inf",
// "-inf" included), epoch = its row index (0, 1, 2, ...: contiguous, in
// order) and, if the header has total_env_steps, (epoch + 1) x the run's
// steps per epoch. Errors name the source and the line (1-based, the header
// is line 1).
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "common/message_text.h"

namespace bsg::algos {

class ProgressLogError : public std::runtime_error {
 public:
  explicit ProgressLogError(const std::string& message) : std::runtime_error(printable_message(message)) {}
};

struct ProgressLogText {
  std::string header;             // "" if the text is empty
  std::vector<std::string> rows;  // complete rows, without newlines
  std::string torn_tail;          // bytes after the last newline ("" if none)
};

// Splits `text` into header, rows and torn tail and checks every complete
// line; throws ProgressLogError "<source>:<line>: <what>" on the first bad one.
// `steps_per_epoch` <= 0 skips the total_env_steps check.
ProgressLogText read_progress_log(std::string_view text, const std::string& source_name, long long steps_per_epoch);

// The text the rows make again: header and rows, each with its newline ("" without a header).
std::string progress_log_text(const ProgressLogText& log, std::size_t rows);

}  // namespace bsg::algos
