#include "experiments/slurm_jobs.h"

#include <unistd.h>

#include <fstream>
#include <sstream>
#include <stdexcept>

#include "common/csv_text.h"
#include "experiments/captured_program.h"

namespace bsg::experiments {

void append_slurm_records(const std::filesystem::path& sweep_dir, const std::vector<SlurmTaskRecord>& records) {
  const std::filesystem::path path = sweep_dir / kSlurmJobsName;
  const bool is_new = !std::filesystem::exists(path);
  std::ofstream file(path, std::ios::app);
  if (!file) throw std::runtime_error("cannot write " + path.string());
  if (is_new) file << "job_id,task,run_dir\n";
  for (const SlurmTaskRecord& record : records) {
    file << record.job_id << "," << record.task << "," << csv_field(record.run_dir.generic_string()) << "\n";
  }
  file.flush();
  if (!file) throw std::runtime_error("cannot write " + path.string());
}

std::vector<SlurmTaskRecord> read_slurm_records(const std::filesystem::path& sweep_dir) {
  const std::filesystem::path path = sweep_dir / kSlurmJobsName;
  std::vector<SlurmTaskRecord> records;
  std::ifstream file(path);
  if (!file) return records;
  std::string line;
  int number = 0;
  while (std::getline(file, line)) {
    ++number;
    if (number == 1 || line.empty()) continue;
    const std::vector<std::string> fields = parse_csv_fields(line);
    SlurmTaskRecord record;
    try {
      if (fields.size() != 3 || fields[0].empty() || fields[2].empty()) throw std::invalid_argument("fields");
      record.job_id = fields[0];
      std::size_t used = 0;
      record.task = std::stoi(fields[1], &used);
      if (used != fields[1].size()) throw std::invalid_argument("task");
    } catch (const std::exception&) {
      throw std::runtime_error(path.string() + " line " + std::to_string(number) +
                               ": expected job_id,task,run_dir, got '" + line + "'");
    }
    record.run_dir = fields[2];
    records.push_back(std::move(record));
  }
  return records;
}

std::map<std::string, SlurmTaskState> parse_squeue_tasks(const std::string& text) {
  std::map<std::string, SlurmTaskState> tasks;
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    const std::size_t bar = line.find('|');
    if (bar == std::string::npos) continue;
    const std::string id = line.substr(0, bar);
    const std::string state = line.substr(bar + 1);
    if (state == "RUNNING" || state == "COMPLETING" || state == "CONFIGURING" || state == "STAGE_OUT" ||
        state == "SIGNALING" || state == "SUSPENDED") {
      tasks[id] = SlurmTaskState::running;
    } else if (state == "PENDING" || state == "REQUEUED" || state == "REQUEUE_HOLD" || state == "REQUEUE_FED" ||
               state == "RESIZING" || state == "RESV_DEL_HOLD") {
      tasks[id] = SlurmTaskState::queued;
    }
  }
  return tasks;
}

std::map<std::string, SlurmTaskState> query_slurm_tasks() {
  const CapturedOutput result =
      run_captured({"squeue", "--noheader", "--array", "--format=%i|%T", "--user=" + std::to_string(::getuid())});
  if (result.exit_code != 0) {
    throw std::runtime_error("squeue failed (exit code " + std::to_string(result.exit_code) + "): " + result.err);
  }
  return parse_squeue_tasks(result.out);
}

std::map<std::filesystem::path, SlurmTaskRecord> latest_record_per_run(const std::vector<SlurmTaskRecord>& records) {
  std::map<std::filesystem::path, SlurmTaskRecord> latest;
  for (const SlurmTaskRecord& record : records) latest[record.run_dir] = record;
  return latest;
}

}  // namespace bsg::experiments
