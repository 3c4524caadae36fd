#include "experiments/sweep_progress.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "algos/training/progress_line.h"

namespace bsg::experiments {

std::string progress_line(const SweepCounts& counts, std::optional<double> eta_seconds,
                          std::size_t bar_width) {
  const std::size_t filled =
      counts.total == 0 ? bar_width : counts.finished * bar_width / counts.total;
  std::string line = "[";
  line.append(filled, '#').append(bar_width - filled, '.').append("] ");
  line += std::to_string(counts.finished) + "/" + std::to_string(counts.total) + " runs done";
  line += ", " + std::to_string(counts.running) + " running";
  if (counts.failed > 0) line += ", " + std::to_string(counts.failed) + " failed";
  line += ", ETA " + (eta_seconds ? algos::format_duration(*eta_seconds) : std::string("--"));
  return line;
}

std::optional<double> estimate_seconds_left(double steps_done, double elapsed_seconds,
                                            double steps_left) {
  if (steps_left <= 0) return 0.0;
  if (steps_done <= 0 || elapsed_seconds <= 0) return std::nullopt;
  return steps_left / (steps_done / elapsed_seconds);
}

std::string format_count(long long count) {
  std::string digits = std::to_string(count < 0 ? -count : count);
  std::string text;
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) text += ' ';
    text += digits[i];
  }
  return (count < 0 ? "-" : "") + text;
}

}  // namespace bsg::experiments
