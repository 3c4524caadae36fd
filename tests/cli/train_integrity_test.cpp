// Resume integrity and messages of `bsg train` end to end (issue 25): a torn
// or lost progress row within the checkpointed epochs is restored and the
// run then equals an uninterrupted one (the oracle); a progress log of
// another run or with rows out of order stops the resume naming the file and
// line; a checkpoint that is a directory is called one; --print-config runs
// the checks training runs; long values are cut and control bytes escaped.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "../test_support.h"
#include "common/csv_text.h"
#include "progress_rows.h"
#include "run_bsg.h"

namespace fs = std::filesystem;
using bsg::testing::read_text_file;
using bsg::testing::run_bsg;
using bsg::testing::TemporaryDirectory;
using bsg::testing::write_text_file;

namespace {

using bsg::testing::kConfigsOption;

std::string run_file(const TemporaryDirectory& dir, const std::string& name, const std::string& env_alg) {
  const fs::path path = dir.path() / name;
  write_text_file(path, env_alg + "seed: 3\nepochs: 3\nsteps_per_epoch: 1000\nsave_freq: 1\neval_episodes: 1\n");
  return path.string();
}

const std::string kBallTrpoL = "env_id: SafetyBallCircle-v0\nalg: lag-trpo\n";

// Trains `file` into `out` for `epochs` epochs, stopping there with a checkpoint; its exit code.
int train_and_stop(const std::string& file, const fs::path& out, int epochs) {
  return run_bsg("train " + file + " --out " + out.string() + kConfigsOption + " --quiet --stop-after " +
                 std::to_string(epochs))
      .exit_code;
}

std::vector<std::size_t> field_counts(const fs::path& progress) {
  std::vector<std::size_t> counts;
  std::ifstream file(progress);
  std::string line;
  while (std::getline(file, line)) counts.push_back(bsg::parse_csv_fields(line).size());
  return counts;
}

// Issue 25, reproduction 1: `head -c -300 progress.csv` after --stop-after 2,
// then --resume, kept the torn row (field counts 47 47 30 47).
TEST(TrainIntegrity, ATornProgressRowIsRestoredAndTheRunEqualsAnUninterruptedOne) {
  TemporaryDirectory dir;
  const std::string file = run_file(dir, "run.yaml", kBallTrpoL);
  const fs::path run = dir.path() / "run";
  const fs::path oracle = dir.path() / "oracle";
  ASSERT_EQ(train_and_stop(file, run, 2), 0);
  const std::string whole = read_text_file(run / "progress.csv");
  ASSERT_GT(whole.size(), 300u);
  write_text_file(run / "progress.csv", whole.substr(0, whole.size() - 300));
  const auto resumed = run_bsg("train --resume " + run.string());
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_NE(resumed.output.find("rows of epochs 1 to 1 restored from the checkpoint"), std::string::npos)
      << resumed.output;
  ASSERT_EQ(run_bsg("train " + file + " --out " + oracle.string() + kConfigsOption + " --quiet").exit_code, 0);
  const std::vector<std::size_t> counts = field_counts(run / "progress.csv");
  ASSERT_EQ(counts.size(), 4u);
  for (const std::size_t count : counts) EXPECT_EQ(count, counts.front());
  EXPECT_EQ(bsg::testing::progress_without_timings(run / "progress.csv"),
            bsg::testing::progress_without_timings(oracle / "progress.csv"));
}

// A checkpoint write killed half-way leaves <file>.tmp.<pid>.<6 characters>;
// the resume removes it (its writer is gone) and says so, and keeps a fresh
// one, which a write on another host could still be using.
TEST(TrainIntegrity, AResumeRemovesTheTemporariesOfKilledWritesAndSaysSo) {
  TemporaryDirectory dir;
  const std::string file = run_file(dir, "run.yaml", kBallTrpoL);
  const fs::path run = dir.path() / "run";
  ASSERT_EQ(train_and_stop(file, run, 2), 0);
  // pid 2^22 + 1 is above Linux's largest pid (pid_max <= 2^22): no process has it.
  const fs::path stale = run / "checkpoint.bin.tmp.4194305.AbCdEf";
  const fs::path fresh = run / "config.yaml.tmp.4194305.GhIjKl";
  write_text_file(stale, "half a checkpoint");
  write_text_file(fresh, "half a config");
  fs::last_write_time(stale, fs::file_time_type::clock::now() - std::chrono::minutes(5));
  const auto resumed = run_bsg("train --resume " + run.string());
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_NE(resumed.output.find("removed 1 stale temporary file left by interrupted writes in " + run.string() +
                                " (first: checkpoint.bin.tmp.4194305.AbCdEf)"),
            std::string::npos)
      << resumed.output;
  EXPECT_FALSE(fs::exists(stale));
  EXPECT_TRUE(fs::exists(fresh));
}

// Issue 25, reproduction 1: a CarRun/cpo run directory holding a BallCircle
// run's progress.csv (as many rows) resumed and finished.
TEST(TrainIntegrity, AProgressLogOfAnotherRunIsRefusedNamingTheFileAndLine) {
  TemporaryDirectory dir;
  const fs::path car = dir.path() / "car";
  const fs::path ball = dir.path() / "ball";
  ASSERT_EQ(train_and_stop(run_file(dir, "car.yaml", "env_id: SafetyCarRun-v0\nalg: cpo\n"), car, 1), 0);
  ASSERT_EQ(train_and_stop(run_file(dir, "ball.yaml", kBallTrpoL), ball, 1), 0);
  fs::copy_file(ball / "progress.csv", car / "progress.csv", fs::copy_options::overwrite_existing);
  const auto resumed = run_bsg("train --resume " + car.string());
  EXPECT_EQ(resumed.exit_code, 1) << resumed.output;
  EXPECT_NE(resumed.output.find((car / "progress.csv").string() + ":1: the header differs from the one the "
                                                                   "checkpoint records: the progress log does not "
                                                                   "belong to this run"),
            std::string::npos)
      << resumed.output;
}

// Issue 25, reproduction 1: rows out of order (epochs 1, 0, 2) were kept.
TEST(TrainIntegrity, RowsOutOfOrderAreRefusedNamingTheLine) {
  TemporaryDirectory dir;
  const fs::path run = dir.path() / "run";
  ASSERT_EQ(train_and_stop(run_file(dir, "run.yaml", kBallTrpoL), run, 2), 0);
  std::ifstream in(run / "progress.csv");
  std::string header, first, second;
  std::getline(in, header);
  std::getline(in, first);
  std::getline(in, second);
  in.close();
  write_text_file(run / "progress.csv", header + "\n" + second + "\n" + first + "\n");
  const auto resumed = run_bsg("train --resume " + run.string());
  EXPECT_EQ(resumed.exit_code, 1) << resumed.output;
  EXPECT_NE(resumed.output.find((run / "progress.csv").string() + ":2: epoch 1 where epoch 0 belongs"),
            std::string::npos)
      << resumed.output;
}

// Issue 25, reproduction 6: a checkpoint that is a directory was called "missing".
TEST(TrainIntegrity, ACheckpointThatIsADirectoryIsCalledOne) {
  TemporaryDirectory dir;
  const fs::path run = dir.path() / "run";
  ASSERT_EQ(train_and_stop(run_file(dir, "run.yaml", kBallTrpoL), run, 1), 0);
  fs::remove(run / "checkpoint.bin");
  fs::create_directory(run / "checkpoint.bin");
  const auto resumed = run_bsg("train --resume " + run.string());
  EXPECT_EQ(resumed.exit_code, 1) << resumed.output;
  EXPECT_NE(resumed.output.find("checkpoint.bin is a directory, not a file"), std::string::npos) << resumed.output;
}

// Issue 25, reproduction 6: --print-config accepted what training rejects.
TEST(TrainIntegrity, PrintConfigRunsTheChecksTrainingRuns) {
  TemporaryDirectory dir;
  const std::string file = run_file(dir, "run.yaml", kBallTrpoL);
  const auto lean = run_bsg("train --print-config " + file + kConfigsOption + " --set physics=lean");
  EXPECT_EQ(lean.exit_code, 1) << lean.output;
  EXPECT_NE(lean.output.find("physics = lean: SafetyBallCircle-v0: the Ball has no lean physics model"),
            std::string::npos)
      << lean.output;
  const auto minibatches = run_bsg("train --print-config " + file + kConfigsOption + " --set num_mini_batches=100");
  EXPECT_EQ(minibatches.exit_code, 1) << minibatches.output;
  EXPECT_NE(minibatches.output.find("value-net minibatch floor(1000 / num_mini_batches = 100) = 10 is below 16"),
            std::string::npos)
      << minibatches.output;
  EXPECT_EQ(run_bsg("train --print-config " + file + kConfigsOption).exit_code, 0);
}

// Issue 25, reproduction 5: hidden_sizes of 262,144 entries passed validation.
TEST(TrainIntegrity, TooManyHiddenLayersAreRefusedNamingTheKey) {
  TemporaryDirectory dir;
  std::string layers;
  for (int i = 0; i < 262144; ++i) layers += i == 0 ? "4" : ",4";
  const std::string file = run_file(dir, "run.yaml", kBallTrpoL + "hidden_sizes: [" + layers + "]\n");
  const auto result = run_bsg("train --print-config " + file + kConfigsOption);
  EXPECT_EQ(result.exit_code, 1) << result.output.substr(0, 2000);
  EXPECT_NE(result.output.find("lists 262144 hidden layers; at most 32 are allowed"), std::string::npos)
      << result.output.substr(0, 2000);
}

// Issue 25, reproduction 5: hidden_sizes [4096, 4096] trained until bad_alloc.
TEST(TrainIntegrity, NetworksBeyondTheMemoryAvailableAreRefusedWithTheEstimate) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "AddressSanitizer reserves terabytes of shadow address space at start, which no ulimit -v leaves";
#endif
  TemporaryDirectory dir;
  const std::string file =
      run_file(dir, "run.yaml", kBallTrpoL + "hidden_sizes: [4096, 4096]\n");
  // A 2 GB address-space limit makes the memory available smaller than the estimate.
  const auto result = bsg::testing::run_command("ulimit -v 2000000 && " + std::string(BSG_BINARY) +
                                                " train --print-config " + file + kConfigsOption);
  EXPECT_EQ(result.exit_code, 1) << result.output;
  EXPECT_NE(result.output.find("hidden_sizes = [4096, 4096] needs an estimated"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("address-space limit (ulimit -v) 1.91 GB"), std::string::npos) << result.output;
}

// Issue 25, reproduction 6: an 8 MB value was echoed whole; control bytes raw.
TEST(TrainIntegrity, LongValuesAreCutWithTheirLengthAndControlBytesEscaped) {
  TemporaryDirectory dir;
  const std::string file = run_file(dir, "run.yaml", kBallTrpoL + "target_kl: " + std::string(8 * 1024 * 1024, 'x') + "\n");
  const auto long_result = run_bsg("train " + file + kConfigsOption);
  EXPECT_EQ(long_result.exit_code, 1);
  EXPECT_LT(long_result.output.size(), 2000u) << long_result.output.substr(0, 2000);
  EXPECT_NE(long_result.output.find("xxx... (8388608 bytes)'"), std::string::npos) << long_result.output.substr(0, 2000);

  const auto control = run_bsg("train " + run_file(dir, "plain.yaml", kBallTrpoL) + kConfigsOption +
                               " --set \"$(printf 'physics=le\\033[31man\\377')\"");
  EXPECT_EQ(control.exit_code, 1) << control.output;
  EXPECT_EQ(control.output.find('\x1b'), std::string::npos) << control.output;
  EXPECT_EQ(control.output.find('\xff'), std::string::npos) << control.output;
  EXPECT_NE(control.output.find("le\\x1B[31man\\xFF"), std::string::npos) << control.output;
}

}  // namespace
