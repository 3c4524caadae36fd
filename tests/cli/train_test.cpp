// `bsg train` and `bsg eval` end to end: the run directory, resume after an
// interruption reproducing an uninterrupted run, and clear errors with a
// non-zero exit for bad input.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "../test_support.h"
#include "progress_rows.h"
#include "run_bsg.h"

namespace fs = std::filesystem;
using bsg::testing::read_csv_rows;
using bsg::testing::read_text_file;
using bsg::testing::run_bsg;
using bsg::testing::TemporaryDirectory;
using bsg::testing::write_text_file;

namespace {

using bsg::testing::kConfigsOption;

// A small TRPO-L run on SafetyBallCircle-v0: 4 episodes per epoch; `extra`
// adds lines to the run file.
std::string tiny_run_file(const TemporaryDirectory& dir, int epochs, const std::string& extra = "") {
  const fs::path path = dir.path() / "run.yaml";
  write_text_file(
      path,
      "env_id: SafetyBallCircle-v0\nalg: lag-trpo\nseed: 3\nepochs: " + std::to_string(epochs) +
          "\nsteps_per_epoch: 1000\nsave_freq: 4\neval_episodes: 2\ncost_limit: 1\n" + extra);
  return path.string();
}

// The PID multiplier with every part of its state in use: integral,
// both EMAs and a two-epoch delay queue.
const std::string kPidSettings =
    "lambda_optimizer: PID\npid_kp: 0.2\npid_ki: 0.05\npid_kd: 0.3\npid_d_delay: 2\n"
    "pid_delta_p_ema_alpha: 0.5\npid_delta_d_ema_alpha: 0.5\n";

using bsg::testing::progress_without_timings;

}  // namespace

TEST(Train, WritesTheRunDirectory) {
  TemporaryDirectory dir;
  const auto result = run_bsg("train " + tiny_run_file(dir, 2) + kConfigsOption + " --out " + dir.str("run"));
  ASSERT_EQ(result.exit_code, 0) << result.output;
  for (const char* file : {"config.yaml", "progress.csv", "checkpoint.bin", "returns.csv", "costs.csv",
                           "evaluation.json"}) {
    EXPECT_TRUE(fs::exists(dir.path() / "run" / file)) << file;
  }
  EXPECT_NE(result.output.find("epoch    2/2"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("lambda"), std::string::npos) << result.output;
  EXPECT_EQ(progress_without_timings(dir.path() / "run" / "progress.csv").size(), 3u);  // header + 2 epochs
  const std::string returns = read_text_file(dir.path() / "run" / "returns.csv");
  EXPECT_EQ(std::count(returns.begin(), returns.end(), '\n'), 2);
  const std::string evaluation = read_text_file(dir.path() / "run" / "evaluation.json");
  EXPECT_NE(evaluation.find("\"episodes\": 2"), std::string::npos) << evaluation;
  EXPECT_NE(evaluation.find("\"mean_length\": 250"), std::string::npos) << evaluation;
}

namespace {

// Trains `run_file` for 6 epochs whole and split after 3 (with a stale row of
// a killed process), and checks that both give the same files.
void expect_resume_reproduces_whole_run(const TemporaryDirectory& dir, const std::string& run_file) {
  const auto whole = run_bsg("train " + run_file + kConfigsOption + " --quiet --out " + dir.str("whole"));
  ASSERT_EQ(whole.exit_code, 0) << whole.output;

  // Stop after 3 epochs; then pretend the process went on to write a row for
  // epoch 3 and was killed before its next checkpoint.
  const auto first = run_bsg("train " + run_file + kConfigsOption + " --stop-after 3 --out " + dir.str("split"));
  ASSERT_EQ(first.exit_code, 0) << first.output;
  EXPECT_NE(first.output.find("--resume"), std::string::npos) << first.output;
  EXPECT_FALSE(fs::exists(dir.path() / "split" / "evaluation.json"));
  // The stale row is well formed (a malformed one is refused: train_integrity_test.cpp).
  const std::vector<std::vector<std::string>> rows = read_csv_rows(dir.path() / "split" / "progress.csv");
  std::vector<std::string> stale = rows.back();
  stale.at(0) = "3";
  stale.at(1) = "4000";  // total_env_steps after epoch 3 of 1000 steps
  std::string stale_line;
  for (const std::string& field : stale) stale_line += (stale_line.empty() ? "" : ",") + field;
  std::ofstream(dir.path() / "split" / "progress.csv", std::ios::app) << stale_line << "\n";

  const auto resumed = run_bsg("train --resume " + dir.str("split"));
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_NE(resumed.output.find("epoch    4/6"), std::string::npos) << resumed.output;
  EXPECT_EQ(resumed.output.find("epoch    3/6"), std::string::npos) << resumed.output;

  const auto expected = progress_without_timings(dir.path() / "whole" / "progress.csv");
  const auto actual = progress_without_timings(dir.path() / "split" / "progress.csv");
  ASSERT_EQ(expected.size(), 7u);
  EXPECT_EQ(actual, expected);
  EXPECT_EQ(read_text_file(dir.path() / "split" / "returns.csv"),
            read_text_file(dir.path() / "whole" / "returns.csv"));
  EXPECT_EQ(read_text_file(dir.path() / "split" / "costs.csv"),
            read_text_file(dir.path() / "whole" / "costs.csv"));
}

}  // namespace

TEST(Train, AResumedRunReproducesAnUninterruptedOne) {
  TemporaryDirectory dir;
  expect_resume_reproduces_whole_run(dir, tiny_run_file(dir, 6));
}

TEST(Train, AResumedPidRunReproducesAnUninterruptedOne) {
  TemporaryDirectory dir;
  expect_resume_reproduces_whole_run(dir, tiny_run_file(dir, 6, kPidSettings));
  // The P, I and D terms are logged, and all three were in play.
  auto columns = bsg::testing::read_csv_columns(dir.path() / "whole" / "progress.csv");
  const std::vector<double>& lambda = columns["lagrange_multiplier"];
  const std::vector<double>& p = columns["pid_p_term"];
  const std::vector<double>& i = columns["pid_i_term"];
  const std::vector<double>& d = columns["pid_d_term"];
  ASSERT_EQ(lambda.size(), 6u);
  ASSERT_EQ(p.size(), 6u);
  ASSERT_EQ(i.size(), 6u);
  ASSERT_EQ(d.size(), 6u);
  for (std::size_t k = 0; k < lambda.size(); ++k) {
    EXPECT_EQ(lambda[k], std::max(0.0, p[k] + i[k] + d[k])) << "epoch " << k;
  }
  EXPECT_GT(*std::max_element(d.begin() + 3, d.end()) + *std::max_element(p.begin() + 3, p.end()), 0.0);
  EXPECT_GT(i.back(), 0.0);
}

TEST(Train, PrintConfigShowsTheResolvedConfiguration) {
  TemporaryDirectory dir;
  const auto result = run_bsg("train --print-config " + tiny_run_file(dir, 2) + kConfigsOption + " --set target_kl=0.005");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  for (const char* line : {"alg: lag-trpo", "target_kl: 0.005", "lambda_lr:", "max_ep_len: 250"}) {
    EXPECT_NE(result.output.find(line), std::string::npos) << line << " in\n" << result.output;
  }
  EXPECT_FALSE(fs::exists(dir.path() / "runs"));
}

TEST(Train, PrintedConfigIsARunFileThatResolvesToItself) {
  // sac-lag.yaml steps its multiplier per update round; the printed epoch schedule must survive
  // being trained from, where a run directory's config.yaml leaves it unsaid.
  TemporaryDirectory dir;
  const auto first = run_bsg("train --print-config" + kConfigsOption +
                             " --set env_id=SafetyBallCircle-v0 --set alg=sac-lag --set multiplier_schedule=epoch");
  ASSERT_EQ(first.exit_code, 0) << first.output;
  EXPECT_NE(first.output.find("\nmultiplier_schedule: epoch"), std::string::npos) << first.output;
  const fs::path printed = dir.path() / "printed.yaml";
  write_text_file(printed, first.output);
  const auto again = run_bsg("train --print-config " + printed.string() + kConfigsOption);
  ASSERT_EQ(again.exit_code, 0) << again.output;
  const auto after_header = [](const std::string& text) { return text.substr(text.find('\n')); };
  EXPECT_EQ(after_header(again.output), after_header(first.output));
}

TEST(Train, AMissingRunFileIsAnErrorNamingIt) {
  const auto result = run_bsg("train /nonexistent/run.yaml" + kConfigsOption);
  EXPECT_NE(result.exit_code, 0);
  EXPECT_NE(result.output.find("/nonexistent/run.yaml"), std::string::npos) << result.output;
}

TEST(Train, AnUnknownKeyIsAnErrorNamingTheKey) {
  TemporaryDirectory dir;
  const auto result = run_bsg("train " + tiny_run_file(dir, 2) + kConfigsOption + " --set no_such_key=3");
  EXPECT_NE(result.exit_code, 0);
  EXPECT_NE(result.output.find("no_such_key"), std::string::npos) << result.output;
}

TEST(Train, MalformedYamlIsAnErrorNamingTheFile) {
  TemporaryDirectory dir;
  write_text_file(dir.path() / "bad.yaml", "env_id: [unclosed\nalg: trpo\n");
  const auto result = run_bsg("train " + dir.str("bad.yaml") + kConfigsOption);
  EXPECT_NE(result.exit_code, 0);
  EXPECT_NE(result.output.find("bad.yaml"), std::string::npos) << result.output;
}

TEST(Train, NoConfigAndNoResumeIsACommandLineError) {
  const auto result = run_bsg("train");
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_NE(result.output.find("CONFIG"), std::string::npos) << result.output;
}

TEST(Train, ResumeOfADirectoryWithoutARunIsAnError) {
  TemporaryDirectory dir;
  const auto result = run_bsg("train --resume " + dir.path().string());
  EXPECT_NE(result.exit_code, 0);
  EXPECT_NE(result.output.find("not a run directory"), std::string::npos) << result.output;
}

TEST(Train, ResumeWithACorruptCheckpointNamesTheFile) {
  TemporaryDirectory dir;
  ASSERT_EQ(run_bsg("train " + tiny_run_file(dir, 3) + kConfigsOption + " --quiet --stop-after 1 --out " + dir.str("run"))
                .exit_code,
            0);
  const fs::path checkpoint = dir.path() / "run" / "checkpoint.bin";
  const std::string bytes = read_text_file(checkpoint);
  write_text_file(checkpoint, bytes.substr(0, bytes.size() / 2));
  const auto result = run_bsg("train --resume " + dir.str("run"));
  EXPECT_NE(result.exit_code, 0);
  EXPECT_NE(result.output.find(checkpoint.string()), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("truncated"), std::string::npos) << result.output;
}

TEST(Train, ANewRunIntoAnExistingRunDirectoryIsRefused) {
  TemporaryDirectory dir;
  const std::string command = "train " + tiny_run_file(dir, 1) + kConfigsOption + " --quiet --out " + dir.str("run");
  ASSERT_EQ(run_bsg(command).exit_code, 0);
  const std::string before = read_text_file(dir.path() / "run" / "progress.csv");
  const auto again = run_bsg(command);
  EXPECT_NE(again.exit_code, 0);
  EXPECT_NE(again.output.find("--resume"), std::string::npos) << again.output;
  EXPECT_EQ(read_text_file(dir.path() / "run" / "progress.csv"), before);
}

TEST(Eval, PrintsJAndHAndPerEpisodeJson) {
  TemporaryDirectory dir;
  ASSERT_EQ(run_bsg("train " + tiny_run_file(dir, 1) + kConfigsOption + " --quiet --out " + dir.str("run")).exit_code, 0);
  const auto plain = run_bsg("eval " + dir.str("run") + " --episodes 2");
  ASSERT_EQ(plain.exit_code, 0) << plain.output;
  EXPECT_NE(plain.output.find("J (mean return)"), std::string::npos) << plain.output;
  EXPECT_NE(plain.output.find("H (mean cost)"), std::string::npos) << plain.output;
  // The same evaluation as the one written at the end of training.
  const auto json = run_bsg("eval " + dir.str("run") + " --json");
  ASSERT_EQ(json.exit_code, 0) << json.output;
  EXPECT_NE(json.output.find("\"returns\": ["), std::string::npos) << json.output;
  EXPECT_NE(json.output.find("\"lengths\": [250, 250]"), std::string::npos) << json.output;
  const std::string first_return = read_text_file(dir.path() / "run" / "returns.csv").substr(0, 8);
  EXPECT_NE(json.output.find("\"returns\": [" + first_return), std::string::npos) << json.output;
}

TEST(Eval, ASampledEvaluationIsRepeatedByEvalAndItsActionsCanBeChosen) {
  TemporaryDirectory dir;
  // One epoch: the last epoch's sigma is sigma_0 = 0.509.
  ASSERT_EQ(run_bsg("train " + tiny_run_file(dir, 1, "sampled_evaluation: true\n") + kConfigsOption + " --quiet --out " +
                    dir.str("run"))
                .exit_code,
            0);
  const std::string written = read_text_file(dir.path() / "run" / "evaluation.json");
  EXPECT_NE(written.find("\"action_std\": 0.509"), std::string::npos) << written;
  // eval repeats it: the same noise stream gives the same first episode.
  const auto sampled = run_bsg("eval " + dir.str("run") + " --json");
  ASSERT_EQ(sampled.exit_code, 0) << sampled.output;
  const std::string first_return = read_text_file(dir.path() / "run" / "returns.csv").substr(0, 8);
  EXPECT_NE(sampled.output.find("\"returns\": [" + first_return), std::string::npos) << sampled.output;
  const auto mean = run_bsg("eval " + dir.str("run") + " --actions mean");
  ASSERT_EQ(mean.exit_code, 0) << mean.output;
  EXPECT_NE(mean.output.find("actions mean (deterministic)"), std::string::npos) << mean.output;
  const auto plain = run_bsg("eval " + dir.str("run"));
  EXPECT_NE(plain.output.find("actions sampled, sigma 0.509"), std::string::npos) << plain.output;
  const auto bad = run_bsg("eval " + dir.str("run") + " --actions noisy");
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.output.find("--actions"), std::string::npos) << bad.output;
}

TEST(Eval, ADirectoryWithoutARunIsAnError) {
  TemporaryDirectory dir;
  const auto result = run_bsg("eval " + dir.path().string());
  EXPECT_NE(result.exit_code, 0);
  EXPECT_NE(result.output.find(dir.path().string()), std::string::npos) << result.output;
}

TEST(Train, AnErrorOnOneMpiRankEndsTheWholeJob) {
  TemporaryDirectory dir;
  const std::string command = "train " + tiny_run_file(dir, 1) + kConfigsOption + " --quiet --out " + dir.str("run");
  ASSERT_EQ(run_bsg(command).exit_code, 0);
  // Only rank 0 checks the run directory: rank 1 goes on into the first
  // collective and must be ended by rank 0's abort, not left waiting.
  const auto [exit_code, output] = bsg::testing::run_command("timeout 120 " + bsg::testing::mpirun_two_ranks() +
                                                             std::string(BSG_BINARY) + " " + command);
  ASSERT_NE(exit_code, -1) << output;
  EXPECT_NE(exit_code, 0) << output;
  EXPECT_NE(exit_code, 124) << "timed out (a rank hung):\n" << output;
  EXPECT_NE(output.find("already holds a run"), std::string::npos) << output;
  EXPECT_NE(output.find("rank 0"), std::string::npos) << output;
}
