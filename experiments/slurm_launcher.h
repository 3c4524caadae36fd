// The Slurm launcher of a sweep: prepares the run directories as the local
// launcher does (sweep_plan.h), writes the job-array script
// (slurm_script.h) into the sweep directory and submits it with sbatch - one
// array task per run that has not finished and whose task is not already
// queued or running (squeue, slurm_jobs.h). Submitting again is therefore
// safe: finished runs are skipped, checkpointed ones resume, live ones are
// left alone.
#pragma once

#include <filesystem>
#include <iosfwd>

#include "experiments/slurm_script.h"
#include "experiments/sweep_plan.h"

namespace bsg::experiments {

struct SlurmLaunchOptions {
  SlurmJobOptions job;
  std::filesystem::path configs_dir;  // handed to each new run's `bsg train --configs`
  std::filesystem::path bsg_program;  // the `bsg` executable the tasks run
  bool dry_run = false;               // print the script; write and submit nothing
};

// Throws std::runtime_error naming Slurm and the option if sbatch or squeue
// is not on PATH, or with sbatch's own message if it refuses the job.
// Returns 0 (also when there is nothing to submit).
int submit_sweep_to_slurm(const SweepPlan& plan, const std::filesystem::path& sweep_dir,
                          const SlurmLaunchOptions& options, std::ostream& out);

}  // namespace bsg::experiments
