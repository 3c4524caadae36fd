// progress.csv (algos/progress_csv.h), the pooled statistics of docs/algorithms.md#across-mpi-ranks
// (algos/epoch_statistics.h), the column names (algos/epoch_log.h) and the
// console line (algos/progress_line.h).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "../test_support.h"
#include "algos/epoch_log.h"
#include "algos/epoch_statistics.h"
#include "algos/progress_csv.h"
#include "algos/progress_line.h"

namespace fs = std::filesystem;
using bsg::testing::read_text_file;
using bsg::testing::TemporaryDirectory;

namespace {

std::vector<bsg::NamedScalar> row(double epoch, double value) { return {{"epoch", epoch}, {"x", value}}; }

}  // namespace

TEST(PoolStatistics, SingleProcessGivesMeanPopulationStdMinMax) {
  Eigen::VectorXd values(4);
  values << 1.0, 2.0, 3.0, 6.0;
  const bsg::PooledStatistics stats = bsg::pool_statistics(values, bsg::MpiContext::single_process());
  EXPECT_EQ(stats.count, 4);
  EXPECT_DOUBLE_EQ(stats.mean, 3.0);
  EXPECT_DOUBLE_EQ(stats.std, std::sqrt((4.0 + 1.0 + 0.0 + 9.0) / 4.0));
  EXPECT_EQ(stats.min, 1.0);
  EXPECT_EQ(stats.max, 6.0);
}

TEST(PoolStatistics, NoValuesGiveNan) {
  const bsg::PooledStatistics stats = bsg::pool_statistics(Eigen::VectorXd(0), bsg::MpiContext::single_process());
  EXPECT_EQ(stats.count, 0);
  EXPECT_TRUE(std::isnan(stats.mean));
  EXPECT_TRUE(std::isnan(stats.max));
}

TEST(ProgressCsv, HeaderFromTheFirstRowThenValuesThatReadBackExactly) {
  TemporaryDirectory dir;
  const fs::path path = dir.path() / "progress.csv";
  bsg::ProgressCsv csv = bsg::ProgressCsv::create(path);
  csv.write_row(row(0, 0.1));
  csv.write_row(row(1, 1.0 / 3.0));
  EXPECT_EQ(read_text_file(path), "epoch,x\n0,0.1\n1,0.3333333333333333\n");
  EXPECT_EQ(std::stod(bsg::format_csv_number(1.0 / 3.0)), 1.0 / 3.0);
}

TEST(ProgressCsv, ARowWithOtherColumnsIsAnError) {
  TemporaryDirectory dir;
  bsg::ProgressCsv csv = bsg::ProgressCsv::create(dir.path() / "progress.csv");
  csv.write_row(row(0, 1));
  EXPECT_THROW(csv.write_row({{"epoch", 1}, {"y", 2}}), std::logic_error);
}

TEST(ProgressCsv, ResumeDropsRowsAfterTheCheckpointAndAppends) {
  TemporaryDirectory dir;
  const fs::path path = dir.path() / "progress.csv";
  {
    bsg::ProgressCsv csv = bsg::ProgressCsv::create(path);
    for (int epoch = 0; epoch < 5; ++epoch) csv.write_row(row(epoch, epoch * 10));
  }
  bsg::ProgressCsv resumed = bsg::ProgressCsv::resume(path, 3);  // checkpoint after 3 epochs
  resumed.write_row(row(3, 99));
  EXPECT_EQ(read_text_file(path), "epoch,x\n0,0\n1,10\n2,20\n3,99\n");
  EXPECT_THROW(resumed.write_row({{"epoch", 4}}), std::logic_error);
}

TEST(ProgressCsv, ResumeWithFewerRowsThanTheCheckpointIsAnError) {
  TemporaryDirectory dir;
  const fs::path path = dir.path() / "progress.csv";
  {
    bsg::ProgressCsv csv = bsg::ProgressCsv::create(path);
    csv.write_row(row(0, 1));
  }
  try {
    bsg::ProgressCsv::resume(path, 4);
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
  }
}

TEST(EpochLog, DiagnosticNamesBecomeClearColumnNames) {
  EXPECT_EQ(bsg::progress_column_name("Loss/Pi"), "policy_loss");
  EXPECT_EQ(bsg::progress_column_name("KL"), "kl");
  EXPECT_EQ(bsg::progress_column_name("LagrangeMultiplier"), "lagrange_multiplier");
  EXPECT_EQ(bsg::progress_column_name("Misc/OptimCase"), "cpo_optim_case");
  EXPECT_EQ(bsg::progress_column_name("Misc/Something_New"), "misc_something_new");
  EXPECT_TRUE(bsg::is_timing_column("time_collect_s"));
  EXPECT_TRUE(bsg::is_timing_column("fps"));
  EXPECT_FALSE(bsg::is_timing_column("episode_return_mean"));
}

TEST(ProgressLine, ShowsEpochReturnCostLimitLambdaKlAndEta) {
  bsg::ProgressLineInputs in;
  in.epoch = 11;
  in.epochs = 500;
  in.mean_return = 31.5;
  in.mean_cost = 40.1;
  in.cost_limit = 25.0;
  in.lagrange_multiplier = 0.051;
  in.kl = 0.00812;
  in.epoch_seconds = 0.38;
  in.eta_seconds = 188;
  const std::string line = bsg::format_progress_line(in);
  for (const char* part : {"12/500", "31.50", "40.10", "limit 25", "lambda 0.0510", "KL 0.00812", "0.38 s", "3m08s"}) {
    EXPECT_NE(line.find(part), std::string::npos) << part << " in " << line;
  }
  EXPECT_EQ(bsg::format_duration(45), "45s");
  EXPECT_EQ(bsg::format_duration(7500), "2h05m");
  EXPECT_EQ(bsg::format_duration(3 * 86400 + 4 * 3600 + 59), "3d04h");  // a sweep's ETA
  EXPECT_EQ(bsg::format_duration(-1), "?");
}
