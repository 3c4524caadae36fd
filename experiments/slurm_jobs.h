// Which Slurm array task trains which run: <sweep>/slurm_jobs.csv (job_id,
// task, run_dir; one line per run submitted, appended), and what squeue says
// of those tasks now. A sweep submitted again skips the runs whose task is
// still queued or running, and `bsg sweep --status` shows them.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace bsg::experiments {

inline constexpr const char* kSlurmJobsName = "slurm_jobs.csv";

struct SlurmTaskRecord {
  std::string job_id;  // the array job's id, e.g. "1234"
  int task = 0;        // the array task id
  std::filesystem::path run_dir;  // relative to the sweep directory
  std::string task_id() const { return job_id + "_" + std::to_string(task); }
};

// Appends the records (writing the header if the file is new).
void append_slurm_records(const std::filesystem::path& sweep_dir, const std::vector<SlurmTaskRecord>& records);
// All records in file order; empty if the file does not exist. Throws
// std::runtime_error naming the file and line if it is malformed.
std::vector<SlurmTaskRecord> read_slurm_records(const std::filesystem::path& sweep_dir);

enum class SlurmTaskState { queued, running };

// Parses `squeue -h -r -o %i|%T` output ("1234_5|PENDING" per line) into
// task id -> state; lines of other jobs are kept too (callers look up theirs).
// States that end a job (COMPLETED, FAILED, CANCELLED, ...) are left out.
std::map<std::string, SlurmTaskState> parse_squeue_tasks(const std::string& text);

// Runs squeue for this user's jobs. Throws std::runtime_error with squeue's
// message if it fails.
std::map<std::string, SlurmTaskState> query_slurm_tasks();

// The latest record of each run (run_dir -> record).
std::map<std::filesystem::path, SlurmTaskRecord> latest_record_per_run(const std::vector<SlurmTaskRecord>& records);

}  // namespace bsg::experiments
