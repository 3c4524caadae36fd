// `bsg sweep --slurm` on a real one-node Slurm cluster (scripts/slurm_local.sh,
// started and stopped by this test; skipped unless root with Slurm and munge
// installed). A small grid is submitted; one array task is cancelled with
// scancel mid-run and the sweep submitted again: the cancelled run resumes
// from its checkpoint, every run finishes exactly once, each progress.csv
// equals the one a local sweep of the same grid writes (timings aside), a
// third submission submits nothing, and `bsg table` tabulates the sweep.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "../test_support.h"
#include "common/csv_text.h"
#include "experiments/grid_expansion.h"
#include "experiments/grid_file.h"
#include "progress_rows.h"
#include "run_bsg.h"

namespace fs = std::filesystem;
using bsg::testing::read_text_file;
using bsg::testing::run_bsg;

namespace {

using bsg::testing::kSource;

using bsg::testing::run_command;


std::size_t count_of(const std::string& text, const std::string& part) {
  std::size_t count = 0;
  for (std::size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++count;
  return count;
}

}  // namespace

// Outside the anonymous namespace: the tests derive from it, and a test file
// compiled in a batch is an included file, where GCC warns about such a base.
class LocalSlurmCluster : public ::testing::Test {
 protected:
  void SetUp() override {
    if (::geteuid() != 0) GTEST_SKIP() << "needs root to start munged, slurmctld and slurmd";
    if (run_command("command -v slurmctld && command -v slurmd && command -v munged").exit_code != 0) {
      GTEST_SKIP() << "Slurm or munge is not installed (scripts/install_deps.sh installs them)";
    }
    dir_ = temp_.path() / "cluster";
    const auto started = run_command("bash " + (kSource / "scripts" / "slurm_local.sh").string() + " start " + dir_.string());
    ASSERT_EQ(started.exit_code, 0) << started.output;
    running_ = true;
    ::setenv("SLURM_CONF", (dir_ / "slurm.conf").c_str(), 1);
  }
  void TearDown() override {
    if (running_) {
      run_command("scancel --user=root --quiet");
      const auto stopped = run_command("bash " + (kSource / "scripts" / "slurm_local.sh").string() + " stop " + dir_.string());
      EXPECT_EQ(stopped.exit_code, 0) << stopped.output;
    }
    ::unsetenv("SLURM_CONF");
  }
  // Waits until squeue lists none of our jobs.
  bool wait_for_empty_queue(int seconds) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(seconds);
    while (std::chrono::steady_clock::now() < deadline) {
      const auto queue = run_command("squeue --noheader --user=root");
      if (queue.exit_code == 0 && queue.output.find_first_not_of(" \n") == std::string::npos) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(200));
    }
    return false;
  }

  bsg::testing::TemporaryDirectory temp_;
  fs::path dir_;
  bool running_ = false;
};

TEST_F(LocalSlurmCluster, ACancelledTaskResumesOnResubmissionAndEveryRunFinishesOnceLikeALocalSweep) {
  // The quick grid's two TRPO seeds with epochs enough to cancel one mid-run: an epoch of 2000
  // steps takes about 0.06 s, so 30 of them leave the cancel well over a second after the first.
  const fs::path grid = temp_.path() / "slurm_quick.yaml";
  std::ofstream(grid) << "envs: [SafetyBallCircle-v0]\nseeds: [0, 1]\n"
                         "fixed: {epochs: 30, steps_per_epoch: 2000, save_freq: 1, eval_episodes: 2}\n"
                         "algorithms: {trpo: {axes: {target_kl: [0.01]}}}\n";
  const fs::path sweep = temp_.path() / "slurm_sweep";
  const std::string submit = "sweep " + grid.string() + " --configs " + (kSource / "configs").string() +
                             " --slurm --max-running 2 --out " + sweep.string();
  std::vector<fs::path> runs;
  for (const bsg::experiments::GridRun& run : bsg::experiments::expand_grid(bsg::experiments::load_grid_file(grid))) runs.push_back(run.relative_dir());
  ASSERT_EQ(runs.size(), 2u);

  const auto first = run_bsg(submit);
  ASSERT_EQ(first.exit_code, 0) << first.output;
  EXPECT_NE(first.output.find("2 to submit"), std::string::npos) << first.output;
  // Cancel task 1 once it has logged an epoch.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (bsg::testing::progress_rows(sweep / runs[1] / "progress.csv") < 1 && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  const std::string job = first.output.substr(first.output.find("job array ") + 10);
  const std::string job_id = job.substr(0, job.find(' '));
  // Cancel first, then ask for the status: the status command's own start-up must not let the run finish.
  ASSERT_EQ(run_command("scancel " + job_id + "_1").exit_code, 0);
  const auto status_live = run_bsg("sweep --status " + sweep.string());
  EXPECT_EQ(status_live.exit_code, 0) << status_live.output;
  ASSERT_TRUE(wait_for_empty_queue(90));
  const int epochs_before = bsg::testing::progress_rows(sweep / runs[1] / "progress.csv");
  EXPECT_GE(epochs_before, 1);
  EXPECT_LT(epochs_before, 30) << "the task was not cancelled mid-run";
  EXPECT_FALSE(fs::exists(sweep / runs[1] / "evaluation.json"));
  const auto stopped = run_bsg("sweep --status " + sweep.string());
  EXPECT_NE(stopped.output.find("1 finished"), std::string::npos) << stopped.output;
  EXPECT_NE(stopped.output.find("1 failed"), std::string::npos) << stopped.output;

  const auto second = run_bsg(submit);
  ASSERT_EQ(second.exit_code, 0) << second.output;
  EXPECT_NE(second.output.find("1 finished, 0 queued, 0 running, 1 to submit"), std::string::npos) << second.output;
  ASSERT_TRUE(wait_for_empty_queue(120));
  const auto third = run_bsg(submit);
  EXPECT_NE(third.output.find("nothing to submit"), std::string::npos) << third.output;

  const fs::path local = temp_.path() / "local_sweep";
  const auto local_run = run_bsg("sweep " + grid.string() + " --configs " + (kSource / "configs").string() +
                                 " --jobs 2 --out " + local.string());
  ASSERT_EQ(local_run.exit_code, 0) << local_run.output;
  for (const fs::path& run : runs) {
    EXPECT_TRUE(fs::exists(sweep / run / "evaluation.json")) << run;
    EXPECT_EQ(bsg::testing::progress_without_timings(sweep / run / "progress.csv"), bsg::testing::progress_without_timings(local / run / "progress.csv")) << run;
    EXPECT_EQ(read_text_file(sweep / run / "evaluation.json"), read_text_file(local / run / "evaluation.json")) << run;
  }
  const std::string log0 = read_text_file(sweep / runs[0] / "train.log");
  const std::string log1 = read_text_file(sweep / runs[1] / "train.log");
  EXPECT_EQ(count_of(log0, "=== bsg sweep: slurm task"), 1u) << log0;
  EXPECT_EQ(count_of(log1, "=== bsg sweep: slurm task"), 2u) << log1;
  EXPECT_EQ(count_of(log1, "/bsg train --resume"), 1u) << log1;  // the second task resumed

  const auto table =
      run_bsg("table " + sweep.string() + " --compare report --configs " + (kSource / "configs").string());
  EXPECT_EQ(table.exit_code, 0) << table.output;
  EXPECT_TRUE(fs::exists(sweep / "table1.md"));
  EXPECT_TRUE(fs::exists(sweep / "table1_compare.csv"));
}

TEST_F(LocalSlurmCluster, ARunOfTwoRanksTrainsUnderMpirunInsideItsAllocationLikeALocalSweep) {
  // --ranks-per-run 2: the task asks for 2 tasks and runs mpirun -np 2 in its
  // allocation; the run equals a local sweep's 2-rank run. Under ASan, Open
  // MPI's own allocations would be reported as leaks by the ranks (the
  // submitting environment reaches the task), so leak checks are off for them.
  ::setenv("ASAN_OPTIONS", "detect_leaks=0", 1);
  const fs::path grid = temp_.path() / "two_ranks.yaml";
  std::ofstream(grid) << "envs: [SafetyBallCircle-v0]\nseeds: [3]\n"
                         "fixed: {epochs: 3, steps_per_epoch: 2000, eval_episodes: 2}\nalgorithms: {lag-trpo: }\n";
  const fs::path sweep = temp_.path() / "slurm_two_ranks";
  const auto submitted = run_bsg("sweep " + grid.string() + " --configs " + (kSource / "configs").string() +
                                 " --slurm --ranks-per-run 2 --out " + sweep.string());
  ASSERT_EQ(submitted.exit_code, 0) << submitted.output;
  EXPECT_NE(read_text_file(sweep / "slurm_array.sh").find("#SBATCH --ntasks=2"), std::string::npos);
  ASSERT_TRUE(wait_for_empty_queue(120));
  const fs::path local = temp_.path() / "local_two_ranks";
  const auto local_run = run_bsg("sweep " + grid.string() + " --configs " + (kSource / "configs").string() +
                                 " --ranks-per-run 2 --out " + local.string());
  ::unsetenv("ASAN_OPTIONS");
  ASSERT_EQ(local_run.exit_code, 0) << local_run.output;
  const fs::path run = bsg::experiments::expand_grid(bsg::experiments::load_grid_file(grid)).front().relative_dir();
  const std::string log = read_text_file(sweep / run / "train.log");
  EXPECT_NE(log.find("on 2 ranks"), std::string::npos) << log;
  ASSERT_TRUE(fs::exists(sweep / run / "evaluation.json")) << log;
  EXPECT_EQ(bsg::testing::progress_without_timings(sweep / run / "progress.csv"),
            bsg::testing::progress_without_timings(local / run / "progress.csv"));
  EXPECT_EQ(read_text_file(sweep / run / "evaluation.json"), read_text_file(local / run / "evaluation.json"));
}

TEST_F(LocalSlurmCluster, SbatchRefusingTheJobShowsItsMessage) {
  const fs::path sweep = temp_.path() / "refused";
  const auto result = run_bsg("sweep " + (kSource / "configs" / "grids" / "quick.yaml").string() +
                              " --slurm --partition no_such_partition --out " + sweep.string());
  EXPECT_NE(result.exit_code, 0);
  EXPECT_NE(result.output.find("sbatch refused"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("partition"), std::string::npos) << result.output;
}
