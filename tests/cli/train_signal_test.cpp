// Preemption-safe `bsg train`: SIGTERM or SIGINT mid-run, alone, and SIGUSR1
// to `mpirun -np 2` (which forwards it to both ranks) stop at the end of an
// epoch with exit code 75, a checkpoint and progress.csv; the resumed run's
// progress.csv equals an uninterrupted run's (the oracle) in every column
// but the timings.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "../test_support.h"
#include "common/csv_text.h"
#include "progress_rows.h"
#include "run_bsg.h"

namespace fs = std::filesystem;
using bsg::testing::read_text_file;
using bsg::testing::run_bsg;

namespace {

using bsg::testing::kSource;

fs::path write_run_file(const fs::path& dir) {
  const fs::path path = dir / "run.yaml";
  std::ofstream(path) << "env_id: SafetyBallCircle-v0\nalg: trpo\nepochs: 8\nsteps_per_epoch: 2000\n"
                         "save_freq: 100\neval_episodes: 2\n";
  return path;
}

std::string train_arguments(const fs::path& run_file, const fs::path& out) {
  return "train " + run_file.string() + " --out " + out.string() + " --configs " + (kSource / "configs").string() +
         " --quiet";
}


// Starts `command` with sh, output appended to `log`; returns its pid.
pid_t start(const std::string& command, const fs::path& log) {
  const pid_t pid = fork();
  if (pid == 0) {
    execl("/bin/sh", "sh", "-c", ("exec " + command + " >> '" + log.string() + "' 2>&1").c_str(),
          static_cast<char*>(nullptr));
    _exit(127);
  }
  return pid;
}

// Signals `pid` once the run has logged an epoch; returns its exit code and
// the seconds from the signal to the exit.
std::pair<int, double> stop_after_first_epoch(pid_t pid, const fs::path& progress, int signal) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  int status = 0;
  while (bsg::testing::progress_rows(progress) < 1 && std::chrono::steady_clock::now() < deadline) {
    if (waitpid(pid, &status, WNOHANG) == pid) return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, 0.0};
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  const auto sent = std::chrono::steady_clock::now();
  kill(pid, signal);
  waitpid(pid, &status, 0);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - sent).count();
  return {WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status), seconds};
}


void check_stopped_resumes_like_uninterrupted(const std::string& launcher, int signal) {
  bsg::testing::TemporaryDirectory temp;
  const fs::path run_file = write_run_file(temp.path());
  const fs::path stopped = temp.path() / "stopped";
  const fs::path reference = temp.path() / "reference";
  const std::string bsg = std::string(BSG_BINARY).append(" ");
  const fs::path log = temp.path() / "output.log";

  const auto [code, seconds] =
      stop_after_first_epoch(start(launcher + bsg + train_arguments(run_file, stopped), log), stopped / "progress.csv", signal);
  EXPECT_EQ(code, 75) << "exit code of a run stopped by signal " << signal << "; output:\n" << read_text_file(log);
  EXPECT_LT(seconds, 30.0);
  const int epochs = bsg::testing::progress_rows(stopped / "progress.csv");
  EXPECT_GE(epochs, 1);
  EXPECT_LT(epochs, 8) << "the signal did not stop the run early";
  EXPECT_TRUE(fs::exists(stopped / "checkpoint.bin"));
  EXPECT_FALSE(fs::exists(stopped / "evaluation.json"));

  // The checkpoint covers every logged epoch: resuming keeps all rows.
  int status = 0;
  waitpid(start(launcher + bsg + "train --resume " + stopped.string() + " --quiet", log), &status, 0);
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << read_text_file(log);
  waitpid(start(launcher + bsg + train_arguments(run_file, reference), log), &status, 0);
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << read_text_file(log);
  EXPECT_EQ(bsg::testing::progress_without_timings(stopped / "progress.csv"), bsg::testing::progress_without_timings(reference / "progress.csv"));
  EXPECT_EQ(read_text_file(stopped / "evaluation.json"), read_text_file(reference / "evaluation.json"));
}

}  // namespace

TEST(TrainSignal, SigtermStopsAtAnEpochEndAndTheResumedRunEqualsAnUninterruptedOne) {
  check_stopped_resumes_like_uninterrupted("", SIGTERM);
}

TEST(TrainSignal, SigintStopsLikewise) {
  bsg::testing::TemporaryDirectory temp;
  const fs::path run_file = write_run_file(temp.path());
  const fs::path out = temp.path() / "run";
  const auto [code, seconds] = stop_after_first_epoch(
      start(std::string(BSG_BINARY).append(" ").append(train_arguments(run_file, out)), temp.path() / "output.log"),
      out / "progress.csv", SIGINT);
  EXPECT_EQ(code, 75);
  EXPECT_LT(bsg::testing::progress_rows(out / "progress.csv"), 8);
  const bsg::testing::ProgramResult resumed = run_bsg("train --resume " + out.string() + " --quiet");
  EXPECT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_EQ(bsg::testing::progress_rows(out / "progress.csv"), 8);
}

TEST(TrainSignal, Sigusr1ToMpirunStopsBothRanksAtTheSameEpochAndTheResumeEqualsAnUninterruptedRun) {
  check_stopped_resumes_like_uninterrupted(bsg::testing::mpirun_two_ranks(), SIGUSR1);
}

TEST(TrainSignal, TheHelpDocumentsTheSignalsAndTheExitCode) {
  const bsg::testing::ProgramResult help = run_bsg("train --help");
  EXPECT_NE(help.output.find("SIGTERM"), std::string::npos) << help.output;
  EXPECT_NE(help.output.find("exit code 75"), std::string::npos) << help.output;
}
