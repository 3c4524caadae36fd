#include "experiments/slurm_script.h"

#include <stdexcept>

#include "algos/training/run_directory.h"
#include "experiments/child_process.h"
#include "experiments/run_lock.h"
#include "experiments/sweep_manifest.h"

namespace bsg::experiments {

namespace {

std::string quoted(const std::string& word) { return command_line_text({word}); }

}  // namespace

std::string slurm_array_spec(const std::vector<int>& tasks, int max_running) {
  std::string spec;
  for (std::size_t i = 0; i < tasks.size();) {
    std::size_t j = i;
    while (j + 1 < tasks.size() && tasks[j + 1] == tasks[j] + 1) ++j;
    if (!spec.empty()) spec += ',';
    spec += std::to_string(tasks[i]);
    if (j > i) spec += '-' + std::to_string(tasks[j]);
    i = j + 1;
  }
  if (max_running > 0) spec += '%' + std::to_string(max_running);
  return spec;
}

std::string slurm_array_script(const SlurmScriptInput& input) {
  if (input.array_tasks.empty()) throw std::invalid_argument("slurm_array_script: no array task");
  const SlurmJobOptions& job = input.job;
  const algos::RunDirectory files(".");  // the trainer's file names
  const std::string sweep = input.sweep_dir.string();
  std::string s;
  s += "#!/bin/bash\n";
  s += "# Slurm job array of the bsg sweep " + sweep + ", written by `bsg sweep --slurm`.\n";
  s += "# Array task i trains run i of the list below with `bsg train` (resumed from its\n";
  s += "# checkpoint if it has one), holding the run's " + std::string(kRunLockName) +
       "; a finished run ends at once.\n";
  s += "# Resubmit by hand: sbatch " + quoted((input.sweep_dir / kSlurmScriptName).string()) + "\n";
  s += "# Progress: bsg sweep --status " + quoted(sweep) + "\n";
  s += "#SBATCH --job-name=" + input.job_name + "\n";
  s += "#SBATCH --array=" + slurm_array_spec(input.array_tasks, job.max_running) + "\n";
  s += "#SBATCH --ntasks=" + std::to_string(job.ranks_per_run) + "\n";
  s += "#SBATCH --cpus-per-task=1\n";
  if (!job.partition.empty()) s += "#SBATCH --partition=" + job.partition + "\n";
  if (!job.time_limit.empty()) s += "#SBATCH --time=" + job.time_limit + "\n";
  s += "#SBATCH --output=" + (input.sweep_dir / kSlurmLogDirName / "%A_%a.out").string() + "\n";
  s += "#SBATCH --open-mode=append\n";
  s += "#SBATCH --requeue\n";
  for (const std::string& arg : job.sbatch_args) s += "#SBATCH " + arg + "\n";
  s += "\nset -u\n";
  s += "sweep=" + quoted(sweep) + "\n";
  s += "bsg=" + quoted(input.bsg_program.string()) + "\n";
  s += "configs=" + quoted(input.configs_dir.string()) + "\n";
  s += "runs=(\n";
  for (std::size_t i = 0; i < input.run_dirs.size(); ++i) {
    s += "  " + quoted(input.run_dirs[i].generic_string()) + "  # " + std::to_string(i) + "\n";
  }
  s += ")\n";
  s += "run=\"$sweep/${runs[$SLURM_ARRAY_TASK_ID]}\"\n";
  s += "task=\"${SLURM_ARRAY_JOB_ID}_${SLURM_ARRAY_TASK_ID}\"\n\n";
  s += "if [ -e \"$run/" + files.evaluation().filename().string() + "\" ]; then\n";
  s += "  echo \"bsg sweep: $run has finished; task $task has nothing to do\"; exit 0\n";
  s += "fi\n";
  s += "mkdir -p \"$run\"\n";
  s += "exec 9>>\"$run/" + std::string(kRunLockName) + "\"  # inherited by bsg train: the lock lasts as long as it runs\n";
  s += "if ! flock --nonblock 9; then\n";
  s += "  echo \"bsg sweep: another process runs $run (it holds its lock); task $task ends\"; exit 0\n";
  s += "fi\n";
  s += "if [ -e \"$run/" + files.checkpoint().filename().string() + "\" ]; then\n";
  s += "  set -- \"$bsg\" train --resume \"$run\"\n";
  s += "else  # leftovers of a start killed before its first checkpoint\n";
  s += "  rm -f \"$run/" + files.progress().filename().string() + "\" \"$run/" +
       files.config().filename().string() + "\"\n";
  s += "  set -- \"$bsg\" train \"$run/" + std::string(kSweepRunFileName) +
       "\" --out \"$run\" --configs \"$configs\"\n";
  s += "fi\n";
  if (job.ranks_per_run > 1) {
    // scancel signals every process of the job, the ranks too; mpirun,
    // signalled as well, would SIGKILL them 2 x odls_base_sigkill_timeout
    // (default 1) seconds later, before they end their epoch.
    s += "export OMPI_MCA_odls_base_sigkill_timeout=${OMPI_MCA_odls_base_sigkill_timeout:-60}\n";
    if (input.allow_mpi_as_root) {
      s += "export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1\n";
    }
    s += "set -- mpirun -np \"$SLURM_NTASKS\" \"$@\"\n";
  }
  s += "echo \"=== bsg sweep: slurm task $task on $(hostname): $*\" >> \"$run/" + std::string(kSweepRunLogName) +
       "\"\n";
  s += "# Exit code 75: stopped by SIGTERM/SIGINT with a checkpoint (requeue or resubmit to go on).\n";
  s += "exec \"$@\" >> \"$run/" + std::string(kSweepRunLogName) + "\" 2>&1\n";
  return s;
}

}  // namespace bsg::experiments
