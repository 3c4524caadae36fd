// progress.csv (algos/training/progress_csv.h), the pooled statistics of docs/algorithms.md#across-mpi-ranks
// (algos/core/epoch_statistics.h), the column names (algos/training/epoch_log.h) and the
// console line (algos/training/progress_line.h).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

#include "../../test_support.h"
#include "algos/training/epoch_log.h"
#include "algos/core/epoch_statistics.h"
#include "algos/training/progress_csv.h"
#include "algos/training/progress_line.h"

namespace fs = std::filesystem;
using bsg::testing::read_text_file;
using bsg::testing::TemporaryDirectory;

namespace {

std::vector<bsg::algos::NamedScalar> row(double epoch, double value) { return {{"epoch", epoch}, {"x", value}}; }

bsg::algos::ProgressResume resume_after(long long epochs, long long steps_per_epoch = 0, std::ostream* notes = nullptr,
                                 std::optional<std::string> recorded = std::nullopt) {
  return bsg::algos::ProgressResume{epochs, std::move(recorded), steps_per_epoch, notes};
}

void write_text(const fs::path& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

std::string resume_error(const fs::path& path, const bsg::algos::ProgressResume& resume) {
  try {
    bsg::algos::ProgressCsv::resume(path, resume);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(PoolStatistics, SingleProcessGivesMeanPopulationStdMinMax) {
  Eigen::VectorXd values(4);
  values << 1.0, 2.0, 3.0, 6.0;
  const bsg::algos::PooledStatistics stats = bsg::algos::pool_statistics(values, bsg::MpiContext::single_process());
  EXPECT_EQ(stats.count, 4);
  EXPECT_DOUBLE_EQ(stats.mean, 3.0);
  EXPECT_DOUBLE_EQ(stats.std, std::sqrt((4.0 + 1.0 + 0.0 + 9.0) / 4.0));
  EXPECT_EQ(stats.min, 1.0);
  EXPECT_EQ(stats.max, 6.0);
}

TEST(PoolStatistics, NoValuesGiveNan) {
  const bsg::algos::PooledStatistics stats = bsg::algos::pool_statistics(Eigen::VectorXd(0), bsg::MpiContext::single_process());
  EXPECT_EQ(stats.count, 0);
  EXPECT_TRUE(std::isnan(stats.mean));
  EXPECT_TRUE(std::isnan(stats.max));
}

TEST(ProgressCsv, HeaderFromTheFirstRowThenValuesThatReadBackExactly) {
  TemporaryDirectory dir;
  const fs::path path = dir.path() / "progress.csv";
  bsg::algos::ProgressCsv csv = bsg::algos::ProgressCsv::create(path);
  csv.write_row(row(0, 0.1));
  csv.write_row(row(1, 1.0 / 3.0));
  EXPECT_EQ(read_text_file(path), "epoch,x\n0,0.1\n1,0.3333333333333333\n");
  EXPECT_EQ(std::stod(bsg::algos::format_csv_number(1.0 / 3.0)), 1.0 / 3.0);
}

TEST(ProgressCsv, ARowWithOtherColumnsIsAnError) {
  TemporaryDirectory dir;
  bsg::algos::ProgressCsv csv = bsg::algos::ProgressCsv::create(dir.path() / "progress.csv");
  csv.write_row(row(0, 1));
  EXPECT_THROW(csv.write_row({{"epoch", 1}, {"y", 2}}), std::logic_error);
}

TEST(ProgressCsv, ResumeDropsRowsAfterTheCheckpointAndAppends) {
  TemporaryDirectory dir;
  const fs::path path = dir.path() / "progress.csv";
  {
    bsg::algos::ProgressCsv csv = bsg::algos::ProgressCsv::create(path);
    for (int epoch = 0; epoch < 5; ++epoch) csv.write_row(row(epoch, epoch * 10));
  }
  bsg::algos::ProgressCsv resumed = bsg::algos::ProgressCsv::resume(path, resume_after(3));  // checkpoint after 3 epochs
  resumed.write_row(row(3, 99));
  EXPECT_EQ(read_text_file(path), "epoch,x\n0,0\n1,10\n2,20\n3,99\n");
  EXPECT_THROW(resumed.write_row({{"epoch", 4}}), std::logic_error);
}

TEST(ProgressCsv, ResumeWithFewerRowsThanTheCheckpointAndNoRecordOfThemIsAnError) {
  TemporaryDirectory dir;
  const fs::path path = dir.path() / "progress.csv";
  {
    bsg::algos::ProgressCsv csv = bsg::algos::ProgressCsv::create(path);
    csv.write_row(row(0, 1));
  }
  const std::string message = resume_error(path, resume_after(4));
  EXPECT_NE(message.find(path.string() + " holds 1 epoch rows, the checkpoint covers 4"), std::string::npos) << message;
}

// Issue 25, reproduction 1: a last row cut mid-line (what a crash during a
// write leaves) was kept and the next row appended after it.
TEST(ProgressCsv, ATornLastRowIsTrimmedOnResumeNeverKept) {
  TemporaryDirectory dir;
  const fs::path path = dir.path() / "progress.csv";
  write_text(path, "epoch,total_env_steps,x\n0,100,1.5\n1,200,2.5\n2,300,3.");
  std::ostringstream notes;
  bsg::algos::ProgressCsv resumed = bsg::algos::ProgressCsv::resume(path, resume_after(2, 100, &notes));
  resumed.write_row({{"epoch", 2}, {"total_env_steps", 300}, {"x", 3.5}});
  EXPECT_EQ(read_text_file(path), "epoch,total_env_steps,x\n0,100,1.5\n1,200,2.5\n2,300,3.5\n");
  EXPECT_NE(notes.str().find(path.string() + ":4 is cut off (8 bytes without a line end"), std::string::npos)
      << notes.str();
}

TEST(ProgressCsv, ATornRowWithinTheCheckpointedEpochsIsRestoredFromTheCheckpoint) {
  TemporaryDirectory dir;
  const fs::path path = dir.path() / "progress.csv";
  const std::string recorded = "epoch,total_env_steps,x\n0,100,1.5\n1,200,2.5\n2,300,3.5\n";
  write_text(path, recorded.substr(0, recorded.size() - 5));  // "epoch 1 whole, epoch 2 torn"
  std::ostringstream notes;
  bsg::algos::ProgressCsv::resume(path, resume_after(3, 100, &notes, recorded));
  EXPECT_EQ(read_text_file(path), recorded);
  EXPECT_NE(notes.str().find("held 2 of the 3 checkpointed epochs' rows; rows of epochs 2 to 2 restored"),
            std::string::npos)
      << notes.str();
}

TEST(ProgressCsv, AMissingLogIsRestoredFromTheCheckpoint) {
  TemporaryDirectory dir;
  const fs::path path = dir.path() / "progress.csv";
  const std::string recorded = "epoch,total_env_steps,x\n0,100,1.5\n";
  bsg::algos::ProgressCsv::resume(path, resume_after(1, 100, nullptr, recorded));
  EXPECT_EQ(read_text_file(path), recorded);
}

// Issue 25, reproduction 1: a progress.csv of another run with as many rows
// resumed and finished.
TEST(ProgressCsv, ALogOfAnotherRunWithAsManyRowsIsAnErrorNamingTheLine) {
  TemporaryDirectory dir;
  const fs::path path = dir.path() / "progress.csv";
  write_text(path, "epoch,total_env_steps,x\n0,100,1.5\n1,200,7.25\n");
  const std::string message =
      resume_error(path, resume_after(2, 100, nullptr, "epoch,total_env_steps,x\n0,100,1.5\n1,200,2.5\n"));
  EXPECT_NE(message.find(path.string() + ":3: epoch 1 differs from the row the checkpoint records"), std::string::npos)
      << message;
  EXPECT_NE(message.find("does not belong to this run"), std::string::npos) << message;
  write_text(path, "epoch,total_env_steps,y\n0,100,1.5\n1,200,2.5\n");
  const std::string header =
      resume_error(path, resume_after(2, 100, nullptr, "epoch,total_env_steps,x\n0,100,1.5\n1,200,2.5\n"));
  EXPECT_NE(header.find(path.string() + ":1: the header differs"), std::string::npos) << header;
}

struct BadLog {
  std::string text;
  std::string error;  // after "<path>:"
};

void PrintTo(const BadLog& log, std::ostream* out) { *out << log.error; }

class ProgressCsvBadLine : public ::testing::TestWithParam<BadLog> {};

// Issue 25, reproduction 1: rows out of order (epochs 1, 0, 2) and rows of
// another field count were kept.
INSTANTIATE_TEST_SUITE_P(
    FieldsEpochsAndSteps, ProgressCsvBadLine,
    ::testing::Values(
        BadLog{"epoch,total_env_steps,x\n1,200,1\n0,100,1\n2,300,1\n", "2: epoch 1 where epoch 0 belongs"},
        BadLog{"epoch,total_env_steps,x\n0,100,1\n0,100,1\n", "3: epoch 0 where epoch 1 belongs"},
        BadLog{"epoch,total_env_steps,x\n0,100,1\n1,200\n2,300,1\n", "3: holds 2 fields, the header 3"},
        BadLog{"epoch,total_env_steps,x\n0,100,1,4\n", "2: holds 4 fields, the header 3"},
        BadLog{"epoch,total_env_steps,x\n0,100,abc\n", "2: column x holds abc, not a number"},
        BadLog{"epoch,total_env_steps,x\n0,100,\x1b[31m\n", "2: column x holds \\x1B[31m, not a number"},
        BadLog{"epoch,total_env_steps,x\n0,100,1\n\n", "3: holds 0 fields, the header 3"},
        BadLog{"epoch,total_env_steps,x\n0,150,1\n", "2: total_env_steps 150 where this run's 100 steps per epoch give 100"},
        BadLog{"x,epoch\n1,0\n", "1: the header's first column is not 'epoch'"},
        // Found by the libFuzzer target: an empty header and rows of no fields.
        BadLog{"\n\n", "1: the header's first column is not 'epoch'"},
        BadLog{"epoch,epoch\n0,0\n", "1: not a progress.csv header (column epoch is empty, repeated"},
        // Found by the libFuzzer target: the right number, not as the writer prints it.
        BadLog{"epoch,total_env_steps,x\n0.0,100,1\n", "2: epoch 0.0 where epoch 0 belongs"}),
    [](const ::testing::TestParamInfo<BadLog>& info) { return "line_" + std::to_string(info.index); });

TEST_P(ProgressCsvBadLine, IsAnErrorNamingTheFileAndLine) {
  TemporaryDirectory dir;
  const fs::path path = dir.path() / "progress.csv";
  write_text(path, GetParam().text);
  const std::string message = resume_error(path, resume_after(1, 100));
  EXPECT_NE(message.find(path.string() + ":" + GetParam().error), std::string::npos) << message;
  EXPECT_EQ(read_text_file(path), GetParam().text) << "an invalid log is left as it was";
}

TEST(ProgressCsv, ALogThatIsADirectoryIsCalledWhatItIs) {
  TemporaryDirectory dir;
  const fs::path path = dir.path() / "progress.csv";
  fs::create_directory(path);
  const std::string message = resume_error(path, resume_after(0));
  EXPECT_NE(message.find(path.string() + " is a directory, not a file"), std::string::npos) << message;
}

TEST(EpochLog, DiagnosticNamesBecomeClearColumnNames) {
  EXPECT_EQ(bsg::algos::progress_column_name("Loss/Pi"), "policy_loss");
  EXPECT_EQ(bsg::algos::progress_column_name("KL"), "kl");
  EXPECT_EQ(bsg::algos::progress_column_name("LagrangeMultiplier"), "lagrange_multiplier");
  EXPECT_EQ(bsg::algos::progress_column_name("Misc/OptimCase"), "cpo_optim_case");
  EXPECT_EQ(bsg::algos::progress_column_name("Misc/Something_New"), "misc_something_new");
  EXPECT_TRUE(bsg::algos::is_timing_column("time_collect_s"));
  EXPECT_TRUE(bsg::algos::is_timing_column("fps"));
  EXPECT_FALSE(bsg::algos::is_timing_column("episode_return_mean"));
}

TEST(ProgressLine, ShowsEpochReturnCostLimitLambdaKlAndEta) {
  bsg::algos::ProgressLineInputs in;
  in.epoch = 11;
  in.epochs = 500;
  in.mean_return = 31.5;
  in.mean_cost = 40.1;
  in.cost_limit = 25.0;
  in.lagrange_multiplier = 0.051;
  in.kl = 0.00812;
  in.epoch_seconds = 0.38;
  in.eta_seconds = 188;
  const std::string line = bsg::algos::format_progress_line(in);
  for (const char* part : {"12/500", "31.50", "40.10", "limit 25", "lambda 0.0510", "KL 0.00812", "0.38 s", "3m08s"}) {
    EXPECT_NE(line.find(part), std::string::npos) << part << " in " << line;
  }
  EXPECT_EQ(bsg::algos::format_duration(45), "45s");
  EXPECT_EQ(bsg::algos::format_duration(7500), "2h05m");
  EXPECT_EQ(bsg::algos::format_duration(3 * 86400 + 4 * 3600 + 59), "3d04h");  // a sweep's ETA
  EXPECT_EQ(bsg::algos::format_duration(-1), "?");
}

TEST(ProgressLine, AnEtaNotKnownYetSaysWhenItWillBe) {
  bsg::algos::ProgressLineInputs in;
  in.epochs = 10;
  in.kl = std::nan("");
  const std::string line = bsg::algos::format_progress_line(in);
  EXPECT_NE(line.find("ETA once learning starts"), std::string::npos) << line;
}
