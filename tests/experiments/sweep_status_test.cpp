// `bsg sweep --status` on sweep directories built by hand: each run's state
// from its files (evaluation.json, a held lock, a failed event, a
// checkpoint), its epochs, and the ETA worked out by hand from the timings
// written into progress.csv.
#include <gtest/gtest.h>
#include <sys/file.h>

#include <filesystem>
#include <fstream>
#include <optional>
#include <string>

#include "../test_support.h"
#include "common/run_config_yaml.h"
#include "experiments/grid_expansion.h"
#include "experiments/grid_file.h"
#include "experiments/run_lock.h"
#include "experiments/sweep_manifest.h"
#include "experiments/sweep_status.h"

namespace fs = std::filesystem;

namespace {

const fs::path kSource(BSG_SOURCE_DIR);

// progress.csv with `rows` epochs, `seconds_per_epoch` apart in time_s.
void write_progress(const fs::path& dir, int rows, double seconds_per_epoch) {
  std::ofstream file(dir / "progress.csv");
  file << "epoch,return,time_s\n";
  for (int i = 0; i < rows; ++i) file << i << ",1.5," << (i + 1) * seconds_per_epoch << "\n";
}

}  // namespace

TEST(SweepStatus, EachRunsStateEpochsAndTheEtaFromMeasuredEpochTimes) {
  bsg::testing::TemporaryDirectory temp;
  const fs::path sweep = temp.path();
  const fs::path grid = kSource / "configs" / "grids" / "quick.yaml";
  const std::vector<bsg::experiments::GridRun> runs = bsg::experiments::expand_grid(bsg::experiments::load_grid_file(grid));
  ASSERT_EQ(runs.size(), 4u);
  bsg::experiments::write_sweep_manifest(sweep, runs);
  std::vector<fs::path> dirs;
  for (const bsg::experiments::GridRun& run : runs) {
    dirs.push_back(sweep / run.relative_dir());
    fs::create_directories(dirs.back());
    std::ofstream(dirs.back() / bsg::experiments::kSweepRunFileName)
        << bsg::to_yaml(bsg::experiments::resolve_grid_run(run, kSource / "configs", grid.string()));
  }
  // 0: finished; 1: running (lock held), 2 of 6 epochs at 4 s; 2: failed
  // (event), 1 epoch at 2 s; 3: stopped, 3 epochs at 2 s.
  write_progress(dirs[0], 6, 1.0);
  std::ofstream(dirs[0] / "evaluation.json") << "{}";
  write_progress(dirs[1], 2, 4.0);
  const std::optional<bsg::experiments::RunLock> held = bsg::experiments::RunLock::try_acquire(dirs[1]);
  ASSERT_TRUE(held);
  write_progress(dirs[2], 1, 2.0);
  std::ofstream(sweep / bsg::experiments::kSweepEventsName)
      << "time,event,run_dir,detail\n2026-01-01T00:00:00,failed," << runs[2].relative_dir().generic_string()
      << ",exit code 1\n";
  write_progress(dirs[3], 3, 2.0);

  // flock() locks belong to an open file: the status's own try sees it held.
  const bsg::experiments::SweepStatus status = bsg::experiments::read_sweep_status(sweep);
  ASSERT_EQ(status.runs.size(), 4u);
  EXPECT_FALSE(status.slurm);
  EXPECT_EQ(status.runs[0].status, bsg::experiments::SweepRunStatus::finished);
  EXPECT_EQ(status.runs[1].status, bsg::experiments::SweepRunStatus::running);
  EXPECT_EQ(status.runs[2].status, bsg::experiments::SweepRunStatus::failed);
  EXPECT_EQ(status.runs[3].status, bsg::experiments::SweepRunStatus::stopped);
  EXPECT_EQ(status.runs[1].epochs_done, 2);
  EXPECT_EQ(status.runs[1].epochs_total, 6);
  EXPECT_DOUBLE_EQ(*status.runs[1].seconds_per_epoch, 4.0);
  // Left: 4 x 4 s + 5 x 2 s + 3 x 2 s = 32 s of work, one run running.
  EXPECT_DOUBLE_EQ(*bsg::experiments::sweep_eta_seconds(status), 32.0);

  const std::string text = bsg::experiments::sweep_status_text(status);
  EXPECT_NE(text.find("1 finished, 1 running, 0 queued, 1 failed, 1 stopped, 0 not started"), std::string::npos)
      << text;
  EXPECT_NE(text.find("log: " + (dirs[2] / "train.log").string()), std::string::npos) << text;
  EXPECT_NE(text.find("ETA 32s"), std::string::npos) << text;
}

TEST(SweepStatus, AFolderThatIsNoSweepIsNamed) {
  bsg::testing::TemporaryDirectory temp;
  try {
    bsg::experiments::read_sweep_status(temp.path());
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("is not a sweep directory"), std::string::npos) << e.what();
  }
}
