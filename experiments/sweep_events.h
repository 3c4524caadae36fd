// sweep_events.csv of a local sweep (experiments/sweep_manifest.h): one line
// per scheduling event, appended and flushed, "time,event,run_dir,detail".
// Events: start, resume (a child started), done, failed, stopped (the child
// stopped at a stop signal with a checkpoint, exit 75), waiting (another
// process holds the run's lock), interrupted (the sweep that started it ended
// while it ran, e.g. killed with SIGKILL, and it did not finish), skip.
#pragma once

#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <utility>

namespace bsg::experiments {

class SweepEventLog {
 public:
  // Opens <sweep_dir>/sweep_events.csv for appending (with its header if new).
  explicit SweepEventLog(const std::filesystem::path& sweep_dir);
  void record(const std::string& event, const std::filesystem::path& run_dir, const std::string& detail);

 private:
  std::ofstream file_;
};

// Local time as 2026-11-26T09:40:19, the time column of sweep_events.csv.
std::string sweep_timestamp();

// The last (event, detail) of each run_dir in <sweep_dir>/sweep_events.csv;
// lines that cannot be parsed (cut by a crash) are skipped.
std::map<std::filesystem::path, std::pair<std::string, std::string>> last_sweep_events(
    const std::filesystem::path& sweep_dir);

}  // namespace bsg::experiments
