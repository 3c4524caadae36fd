#include "experiments/sweep_events.h"

#include <ctime>
#include <stdexcept>
#include <vector>

#include "common/csv_text.h"
#include "experiments/sweep_manifest.h"

namespace bsg::experiments {

std::string sweep_timestamp() {
  const std::time_t now = std::time(nullptr);
  std::tm local{};
  localtime_r(&now, &local);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%S", &local);
  return text;
}

SweepEventLog::SweepEventLog(const std::filesystem::path& sweep_dir) {
  const std::filesystem::path path = sweep_dir / kSweepEventsName;
  const bool is_new = !std::filesystem::exists(path);
  file_.open(path, std::ios::app);
  if (!file_) throw std::runtime_error("cannot write " + path.string());
  if (is_new) file_ << "time,event,run_dir,detail\n" << std::flush;
}

void SweepEventLog::record(const std::string& event, const std::filesystem::path& run_dir, const std::string& detail) {
  // One string, one write: a crash cuts at most this line.
  const std::string line =
      sweep_timestamp() + "," + event + "," + csv_field(run_dir.generic_string()) + "," + csv_field(detail) + "\n";
  file_ << line << std::flush;
}

std::map<std::filesystem::path, std::pair<std::string, std::string>> last_sweep_events(
    const std::filesystem::path& sweep_dir) {
  std::map<std::filesystem::path, std::pair<std::string, std::string>> events;
  std::ifstream file(sweep_dir / kSweepEventsName);
  std::string line;
  bool header = true;
  while (std::getline(file, line)) {
    if (header) {
      header = false;
      continue;
    }
    std::vector<std::string> fields;
    try {
      fields = parse_csv_fields(line);
    } catch (const std::exception&) {
      continue;  // a line cut by a crash: the others still count
    }
    if (fields.size() == 4) events[fields[2]] = {fields[1], fields[3]};
  }
  return events;
}

}  // namespace bsg::experiments
