// The Slurm job-array script of `bsg sweep --slurm`, as text (a pure
// function: tests read it without Slurm). Array task i trains run i of the
// script's list: it takes the run lock (flock on train.lock, as the local
// launcher does), ends at once if the run has finished or another process
// holds the lock, and otherwise execs `bsg train` - `--resume` if the run has
// a checkpoint (a requeued or resubmitted task continues from it), a fresh
// start from the run's resolved run.yaml if not - with its output appended to
// the run's train.log. With K ranks per run the task asks for K Slurm tasks
// and runs `mpirun -np $SLURM_NTASKS` inside its allocation.
//
// The script stays valid after submission: `sbatch <sweep>/slurm_array.sh`
// resubmits the same tasks by hand (finished runs end at once).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace bsg::experiments {

inline constexpr const char* kSlurmScriptName = "slurm_array.sh";
inline constexpr const char* kSlurmLogDirName = "slurm";  // <sweep>/slurm/<job>_<task>.out

struct SlurmJobOptions {
  std::string partition;   // --partition; empty: the cluster's default
  std::string time_limit;  // --time per run; empty: the partition's default
  int ranks_per_run = 1;   // K: --ntasks=K and mpirun -np K
  int max_running = 0;     // the %M throttle of --array; 0: none
  std::vector<std::string> sbatch_args;  // extra #SBATCH lines, as given
};

struct SlurmScriptInput {
  std::string job_name;
  std::filesystem::path sweep_dir;    // absolute
  std::filesystem::path bsg_program;  // absolute
  std::filesystem::path configs_dir;  // absolute
  std::vector<std::filesystem::path> run_dirs;  // relative to sweep_dir; index = array task id
  std::vector<int> array_tasks;                 // the task ids to run (ascending)
  SlurmJobOptions job;
  bool allow_mpi_as_root = false;  // export Open MPI's consent to run as root
};

// "0-2,5,7-8%4": ranges of consecutive ids, then the throttle if any.
std::string slurm_array_spec(const std::vector<int>& tasks, int max_running);

std::string slurm_array_script(const SlurmScriptInput& input);

}  // namespace bsg::experiments
