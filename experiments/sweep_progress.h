// The progress line of `bsg sweep`: a bar of finished runs out of all, the
// running and failed counts, and the estimated time left. The estimate
// divides the env steps still to do by the steps done per second since the
// sweep started (all parallel jobs together), counting the epochs each
// running run has logged, so runs of different budgets weigh correctly.
#pragma once

#include <cstddef>
#include <optional>
#include <string>

namespace bsg::experiments {

struct SweepCounts {
  std::size_t total = 0;     // runs this sweep covers
  std::size_t finished = 0;  // including those finished before it started
  std::size_t running = 0;
  std::size_t failed = 0;
};

// "[##########..........] 12/40 runs done, 2 running, 1 failed, ETA 1h05m"
std::string progress_line(const SweepCounts& counts, std::optional<double> eta_seconds,
                          std::size_t bar_width = 30);

// Seconds left at the measured rate; nullopt until some steps are done.
std::optional<double> estimate_seconds_left(double steps_done, double elapsed_seconds,
                                            double steps_left);

// 12345678 -> "12 345 678".
std::string format_count(long long count);

}  // namespace bsg::experiments
