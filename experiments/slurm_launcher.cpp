#include "experiments/slurm_launcher.h"

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <map>
#include <ostream>
#include <stdexcept>

#include "common/atomic_file.h"
#include "experiments/captured_program.h"
#include "experiments/run_lock.h"
#include "experiments/slurm_jobs.h"

namespace bsg::experiments {

namespace {

void require_program(const std::string& program) {
  if (!find_on_path(program)) {
    throw std::runtime_error("--slurm: the Slurm command '" + program +
                             "' is not on PATH; install Slurm's client commands (Debian: slurm-client) or "
                             "run the sweep on this machine without --slurm");
  }
}

// The runs whose latest Slurm task is still queued or running.
std::map<std::filesystem::path, SlurmTaskState> live_runs(const std::filesystem::path& sweep_dir) {
  std::map<std::filesystem::path, SlurmTaskState> live;
  const std::vector<SlurmTaskRecord> records = read_slurm_records(sweep_dir);
  if (records.empty()) return live;
  const std::map<std::string, SlurmTaskState> tasks = query_slurm_tasks();
  for (const auto& [run_dir, record] : latest_record_per_run(records)) {
    const auto found = tasks.find(record.task_id());
    if (found != tasks.end()) live[run_dir] = found->second;
  }
  return live;
}

bool locked_by_another_process(const std::filesystem::path& run_dir) {
  if (!std::filesystem::exists(run_dir / kRunLockName)) return false;
  return !RunLock::try_acquire(run_dir).has_value();
}

std::string job_id_of(const std::string& parsable) {
  // sbatch --parsable prints "<id>" or "<id>;<cluster>".
  std::string id = parsable.substr(0, parsable.find_first_of(";\n"));
  if (id.empty() || id.find_first_not_of("0123456789") != std::string::npos) {
    throw std::runtime_error("sbatch printed no job id: '" + parsable + "'");
  }
  return id;
}

}  // namespace

int submit_sweep_to_slurm(const SweepPlan& plan, const std::filesystem::path& sweep_dir,
                          const SlurmLaunchOptions& options, std::ostream& out) {
  if (!options.dry_run) {
    require_program("sbatch");
    require_program("squeue");
  }
  const std::filesystem::path sweep = std::filesystem::absolute(sweep_dir).lexically_normal();
  const std::map<std::filesystem::path, SlurmTaskState> live =
      options.dry_run && !find_on_path("squeue") ? std::map<std::filesystem::path, SlurmTaskState>{}
                                                 : live_runs(sweep_dir);

  SlurmScriptInput input;
  input.job_name = "bsg-" + sweep.filename().string();
  input.sweep_dir = sweep;
  input.bsg_program = options.bsg_program;
  input.configs_dir = std::filesystem::absolute(options.configs_dir).lexically_normal();
  input.job = options.job;
  input.allow_mpi_as_root = ::geteuid() == 0;
  std::size_t finished = 0;
  std::size_t queued = 0;
  std::size_t running = 0;
  std::vector<SlurmTaskRecord> records;
  for (std::size_t i = 0; i < plan.runs.size(); ++i) {
    const PlannedRun& run = plan.runs[i];
    const std::filesystem::path relative = run.run.relative_dir();
    input.run_dirs.push_back(relative);
    if (run.state == RunState::finished) {
      ++finished;
      continue;
    }
    const auto found = live.find(relative);
    if (found != live.end()) {
      ++(found->second == SlurmTaskState::queued ? queued : running);
      continue;
    }
    if (locked_by_another_process(run.dir)) {  // e.g. a local sweep runs it
      ++running;
      continue;
    }
    input.array_tasks.push_back(static_cast<int>(i));
    records.push_back(SlurmTaskRecord{"", static_cast<int>(i), relative});
  }
  const std::string summary = std::to_string(plan.runs.size()) + " runs: " + std::to_string(finished) +
                              " finished, " + std::to_string(queued) + " queued, " + std::to_string(running) +
                              " running, " + std::to_string(records.size()) + " to submit";
  if (records.empty()) {
    out << "bsg sweep --slurm: " << summary << "; nothing to submit\n";
    return 0;
  }
  const std::string script = slurm_array_script(input);
  const std::filesystem::path script_path = sweep / kSlurmScriptName;
  if (options.dry_run) {
    out << "# bsg sweep --slurm --dry-run: " << summary << "; would write " << script_path.string()
        << " and submit it with sbatch\n"
        << script;
    return 0;
  }

  for (const PlannedRun& run : plan.runs) {
    if (run.state != RunState::finished) prepare_run_directory(run);
  }
  std::filesystem::create_directories(sweep / kSlurmLogDirName);
  write_file_atomically(script_path, script);
  std::filesystem::permissions(script_path, std::filesystem::perms::owner_exec, std::filesystem::perm_options::add);
  const auto started = std::chrono::steady_clock::now();
  const CapturedOutput result = run_captured({"sbatch", "--parsable", script_path.string()});
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  if (result.exit_code != 0) {
    throw std::runtime_error("sbatch refused the job array " + script_path.string() + " (exit code " +
                             std::to_string(result.exit_code) + "): " + result.err + result.out);
  }
  const std::string job_id = job_id_of(result.out);
  for (SlurmTaskRecord& record : records) record.job_id = job_id;
  append_slurm_records(sweep, records);
  char took[32];
  std::snprintf(took, sizeof took, "%.2f s", seconds);
  out << "bsg sweep --slurm: " << summary << "; submitted job array " << job_id << " ("
      << slurm_array_spec(input.array_tasks, options.job.max_running) << ", sbatch took " << took << ")\n"
      << "  script: " << script_path.string() << "\n  status: bsg sweep --status " << sweep.string() << "\n";
  return 0;
}

}  // namespace bsg::experiments
