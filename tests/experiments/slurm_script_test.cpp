// The Slurm job-array script and the Slurm bookkeeping of a sweep, without
// Slurm: the array spec against hand-written ranges, the script's lines
// against what sbatch and bash need, squeue's output read by hand-made
// examples, and the job records written and read back.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "../test_support.h"
#include "experiments/slurm_jobs.h"
#include "experiments/slurm_script.h"

namespace fs = std::filesystem;

namespace {

bsg::experiments::SlurmScriptInput example_input() {
  bsg::experiments::SlurmScriptInput input;
  input.job_name = "bsg-quick";
  input.sweep_dir = "/data/sweeps/quick";
  input.bsg_program = "/opt/bsg/bin/bsg";
  input.configs_dir = "/opt/bsg/configs";
  input.run_dirs = {"SafetyBallCircle-v0/trpo/target_kl=0.01/seed=0", "SafetyBallCircle-v0/trpo/target_kl=0.01/seed=1",
                    "SafetyBallCircle-v0/lag-trpo/target_kl=0.01/seed=0"};
  input.array_tasks = {0, 2};
  input.job.max_running = 8;
  return input;
}

bool has_line(const std::string& text, const std::string& line) {
  return ("\n" + text + "\n").find("\n" + line + "\n") != std::string::npos;
}

}  // namespace

TEST(SlurmArraySpec, RangesOfConsecutiveTasksThenTheThrottle) {
  EXPECT_EQ(bsg::experiments::slurm_array_spec({0, 1, 2, 5, 7, 8}, 4), "0-2,5,7-8%4");
  EXPECT_EQ(bsg::experiments::slurm_array_spec({3}, 0), "3");
  EXPECT_EQ(bsg::experiments::slurm_array_spec({0, 2, 4}, 1), "0,2,4%1");
}

TEST(SlurmScript, HasTheDirectivesSbatchReadsBeforeTheFirstCommand) {
  bsg::experiments::SlurmScriptInput input = example_input();
  input.job.partition = "short";
  input.job.time_limit = "02:00:00";
  input.job.sbatch_args = {"--account=abc", "--mem-per-cpu=2G"};
  const std::string script = bsg::experiments::slurm_array_script(input);
  EXPECT_EQ(script.rfind("#!/bin/bash\n", 0), 0u);
  for (const std::string line :
       {"#SBATCH --job-name=bsg-quick", "#SBATCH --array=0,2%8", "#SBATCH --ntasks=1", "#SBATCH --partition=short",
        "#SBATCH --time=02:00:00", "#SBATCH --output=/data/sweeps/quick/slurm/%A_%a.out", "#SBATCH --requeue",
        "#SBATCH --account=abc", "#SBATCH --mem-per-cpu=2G"}) {
    EXPECT_TRUE(has_line(script, line)) << line << "\n" << script;
  }
  // sbatch stops reading directives at the first command.
  const std::size_t last_directive = script.rfind("#SBATCH");
  const std::size_t first_command = script.find("\nset -u");
  EXPECT_LT(last_directive, first_command);
  // Every run listed, indexed by array task id; quoted for bash ('=' is plain).
  EXPECT_TRUE(has_line(script, "  SafetyBallCircle-v0/lag-trpo/target_kl=0.01/seed=0  # 2")) << script;
  EXPECT_NE(script.find("train --resume \"$run\""), std::string::npos);
  EXPECT_NE(script.find("train \"$run/run.yaml\" --out \"$run\" --configs \"$configs\""), std::string::npos);
  EXPECT_NE(script.find("flock --nonblock 9"), std::string::npos);
  EXPECT_EQ(script.find("mpirun"), std::string::npos);  // one rank per run: no MPI launcher
}

TEST(SlurmScript, WithoutPartitionOrTimeTheClusterDefaultsApply) {
  const std::string script = bsg::experiments::slurm_array_script(example_input());
  EXPECT_EQ(script.find("--partition"), std::string::npos);
  EXPECT_EQ(script.find("--time"), std::string::npos);
}

TEST(SlurmScript, KRanksPerRunAskForKTasksAndRunMpirunInsideTheAllocation) {
  bsg::experiments::SlurmScriptInput input = example_input();
  input.job.ranks_per_run = 4;
  input.allow_mpi_as_root = true;
  const std::string script = bsg::experiments::slurm_array_script(input);
  EXPECT_TRUE(has_line(script, "#SBATCH --ntasks=4"));
  EXPECT_TRUE(has_line(script, "set -- mpirun -np \"$SLURM_NTASKS\" \"$@\""));
  EXPECT_NE(script.find("OMPI_ALLOW_RUN_AS_ROOT=1"), std::string::npos);
  EXPECT_NE(script.find("OMPI_MCA_odls_base_sigkill_timeout"), std::string::npos);
}

TEST(SlurmScript, PathsWithSpacesAreQuotedForBash) {
  bsg::experiments::SlurmScriptInput input = example_input();
  input.sweep_dir = "/data/my sweeps/quick";
  const std::string script = bsg::experiments::slurm_array_script(input);
  EXPECT_TRUE(has_line(script, "sweep='/data/my sweeps/quick'")) << script;
}

TEST(SlurmScript, NoTaskIsAnError) {
  bsg::experiments::SlurmScriptInput input = example_input();
  input.array_tasks.clear();
  EXPECT_THROW(bsg::experiments::slurm_array_script(input), std::invalid_argument);
}

TEST(Squeue, ArrayTasksAreQueuedOrRunningAndEndedStatesAreLeftOut) {
  const auto tasks = bsg::experiments::parse_squeue_tasks(
      "17_0|RUNNING\n17_1|PENDING\n17_2|COMPLETING\n18_0|REQUEUED\n18_1|CANCELLED\n19|RUNNING\ngarbage\n");
  ASSERT_EQ(tasks.size(), 5u);
  EXPECT_EQ(tasks.at("17_0"), bsg::experiments::SlurmTaskState::running);
  EXPECT_EQ(tasks.at("17_1"), bsg::experiments::SlurmTaskState::queued);
  EXPECT_EQ(tasks.at("17_2"), bsg::experiments::SlurmTaskState::running);
  EXPECT_EQ(tasks.at("18_0"), bsg::experiments::SlurmTaskState::queued);
  EXPECT_EQ(tasks.count("18_1"), 0u);
}

TEST(SlurmRecords, AppendedRecordsReadBackAndTheLatestPerRunWins) {
  bsg::testing::TemporaryDirectory temp;
  bsg::experiments::append_slurm_records(temp.path(), {{"17", 0, "A/trpo/x=1,y=2/seed=0"}, {"17", 1, "A/trpo/x=1,y=2/seed=1"}});
  bsg::experiments::append_slurm_records(temp.path(), {{"21", 1, "A/trpo/x=1,y=2/seed=1"}});
  const auto records = bsg::experiments::read_slurm_records(temp.path());
  ASSERT_EQ(records.size(), 3u);
  EXPECT_EQ(records[0].run_dir, fs::path("A/trpo/x=1,y=2/seed=0"));
  const auto latest = bsg::experiments::latest_record_per_run(records);
  EXPECT_EQ(latest.at("A/trpo/x=1,y=2/seed=1").task_id(), "21_1");
  EXPECT_EQ(latest.at("A/trpo/x=1,y=2/seed=0").task_id(), "17_0");
}

TEST(SlurmRecords, AMalformedLineIsNamed) {
  bsg::testing::TemporaryDirectory temp;
  std::ofstream(temp.path() / bsg::experiments::kSlurmJobsName) << "job_id,task,run_dir\n17,x,A\n";
  try {
    bsg::experiments::read_slurm_records(temp.path());
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("line 2"), std::string::npos) << e.what();
  }
}
