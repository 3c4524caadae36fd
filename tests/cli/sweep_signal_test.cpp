// `bsg sweep` under signals and a second sweep (issue 25): SIGTERM, SIGINT or
// SIGHUP to the sweep alone stops its children at the end of their epoch
// with a checkpoint, each recorded as stopped, and the sweep exits 75; the
// rerun finishes every run exactly once, with the progress logs (timings
// aside) and evaluations of an uninterrupted sweep (the oracle). After a
// SIGKILL of the sweep alone its children run on; a rerun waits for them and
// the event log ends with each run done. A second sweep on a directory in
// use names the first's pid and exits 1.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "../test_support.h"
#include "algos/training/run_directory.h"
#include "common/csv_text.h"
#include "experiments/grid_expansion.h"
#include "experiments/grid_file.h"
#include "experiments/run_results.h"
#include "experiments/sweep_manifest.h"
#include "progress_rows.h"
#include "run_bsg.h"
#include "sweep_processes.h"

namespace fs = std::filesystem;
using bsg::testing::read_text_file;
using bsg::testing::run_bsg;
using bsg::testing::TemporaryDirectory;

namespace {

using bsg::testing::kSource;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// Two TRPO runs on SafetyBallCircle-v0 (seeds 3 and 4), 30 epochs of 500 steps: long
// enough that neither finishes in the moment between the signal and its epoch end.
struct TinySweep {
  TinySweep() {
    std::ofstream(grid) << "envs: [SafetyBallCircle-v0]\nseeds: [3, 4]\n"
                           "fixed: {epochs: 30, steps_per_epoch: 500, save_freq: 100, eval_episodes: 2}\n"
                           "algorithms: {trpo: }\n";
  }
  std::string arguments(const fs::path& out) const {
    return grid.string() + " --jobs 2 --configs " + (kSource / "configs").string() + " --out " + out.string();
  }
  std::vector<fs::path> run_dirs(const fs::path& out) const {
    std::vector<fs::path> dirs;
    for (const bsg::experiments::GridRun& run : bsg::experiments::expand_grid(bsg::experiments::load_grid_file(grid))) dirs.push_back(out / run.relative_dir());
    return dirs;
  }
  TemporaryDirectory temp;
  fs::path grid = temp.path() / "tiny.yaml";
};

// (event, run_dir) of every line of sweep_events.csv.
std::vector<std::pair<std::string, std::string>> events_of(const fs::path& out) {
  std::vector<std::pair<std::string, std::string>> events;
  std::istringstream lines(read_text_file(out / bsg::experiments::kSweepEventsName));
  std::string line;
  std::getline(lines, line);  // header
  while (std::getline(lines, line)) {
    const std::vector<std::string> fields = bsg::parse_csv_fields(line);
    events.emplace_back(fields.at(1), fields.at(2));
  }
  return events;
}

std::size_t count(const std::vector<std::pair<std::string, std::string>>& events, const std::string& event,
                  const std::string& run) {
  std::size_t n = 0;
  for (const auto& [name, dir] : events) n += name == event && dir == run ? 1 : 0;
  return n;
}

// Waits (60 s at most) until every run has logged `epochs` epochs; false if the sweep ended first.
bool wait_for_epochs(pid_t sweep, const std::vector<fs::path>& runs, int epochs) {
  const auto deadline = Clock::now() + std::chrono::seconds(60);
  while (Clock::now() < deadline) {
    int status = 0;
    if (waitpid(sweep, &status, WNOHANG) == sweep) return false;
    bool all = true;
    for (const fs::path& run : runs) all &= bsg::testing::progress_rows(bsg::algos::RunDirectory(run).progress()) >= epochs;
    if (all) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return false;
}

// Starts the sweep into `out` and waits until each run has logged an epoch;
// -1 if the sweep ended first.
pid_t start_and_wait_for_first_epochs(const TinySweep& sweep, const fs::path& out, const fs::path& log) {
  const pid_t pid = bsg::testing::start_sweep_in_own_group(sweep.arguments(out), log);
  return wait_for_epochs(pid, sweep.run_dirs(out), 1) ? pid : -1;
}

int exit_code_of(int status) { return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status); }

class SweepStopSignal : public ::testing::TestWithParam<int> {};

INSTANTIATE_TEST_SUITE_P(TermIntHup, SweepStopSignal, ::testing::Values(SIGTERM, SIGINT, SIGHUP),
                         [](const ::testing::TestParamInfo<int>& info) {
                           return std::string(sigabbrev_np(info.param));
                         });

// Issue 25, reproduction 3: SIGTERM to `bsg sweep` orphaned its children.
TEST_P(SweepStopSignal, StopsChildrenWithCheckpointsAndTheRerunMatchesAnUninterruptedSweep) {
  const TinySweep sweep;
  const fs::path out = sweep.temp.path() / "stopped";
  const fs::path reference = sweep.temp.path() / "reference";
  const std::vector<fs::path> runs = sweep.run_dirs(out);
  const fs::path log = sweep.temp.path() / "first.log";

  const pid_t pid = start_and_wait_for_first_epochs(sweep, out, log);
  ASSERT_GT(pid, 0) << read_text_file(log);
  const auto signalled = Clock::now();
  ASSERT_EQ(kill(pid, GetParam()), 0);  // the sweep alone, not its group
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  const double stop_seconds = seconds_since(signalled);
  const std::string output = read_text_file(log);
  const std::string signal = std::string("SIG") + sigabbrev_np(GetParam());
  EXPECT_EQ(exit_code_of(status), 75) << output;
  EXPECT_NE(output.find("bsg sweep: " + signal + " received: no new run starts; asking the 2 running runs to stop"),
            std::string::npos)
      << output;
  EXPECT_NE(output.find("bsg sweep: stopped by " + signal + ": 2 runs stopped with a checkpoint, 0 not started, 0 of 2 "
                        "finished; run the same bsg sweep command again to resume"),
            std::string::npos)
      << output;
  EXPECT_EQ(bsg::testing::live_processes_in_group(pid), 0) << "no child left running";
  for (const fs::path& run : runs) {
    const std::string name = fs::relative(run, out).generic_string();
    EXPECT_EQ(bsg::experiments::run_state(bsg::algos::RunDirectory(run)), bsg::experiments::RunState::resumable) << name;
    const auto events = events_of(out);
    ASSERT_FALSE(events.empty());
    EXPECT_EQ(count(events, "stopped", name), 1u) << name;
    EXPECT_NE(read_text_file(run / bsg::experiments::kSweepRunLogName).find("stop signal received"), std::string::npos) << name;
  }
  const std::size_t events_before = events_of(out).size();

  const auto rerun_start = Clock::now();
  const auto rerun = run_bsg("sweep " + sweep.arguments(out));
  const double rerun_seconds = seconds_since(rerun_start);
  ASSERT_EQ(rerun.exit_code, 0) << rerun.output;
  const auto reference_start = Clock::now();
  const auto uninterrupted = run_bsg("sweep " + sweep.arguments(reference));
  const double reference_seconds = seconds_since(reference_start);
  ASSERT_EQ(uninterrupted.exit_code, 0) << uninterrupted.output;
  std::printf("[ figures  ] %s: sweep stopped %.2f s after the signal; rerun %.2f s; uninterrupted sweep %.2f s\n",
              signal.c_str(), stop_seconds, rerun_seconds, reference_seconds);

  const auto events = events_of(out);
  const std::vector<fs::path> reference_runs = sweep.run_dirs(reference);
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const std::string name = fs::relative(runs[i], out).generic_string();
    const std::vector<std::pair<std::string, std::string>> after(events.begin() + static_cast<long>(events_before),
                                                                  events.end());
    EXPECT_EQ(count(after, "resume", name), 1u) << name;
    EXPECT_EQ(count(after, "start", name), 0u) << name;
    EXPECT_EQ(count(after, "done", name), 1u) << name;
    const bsg::algos::RunDirectory stopped(runs[i]);
    const bsg::algos::RunDirectory oracle(reference_runs[i]);
    EXPECT_EQ(bsg::testing::progress_without_timings(stopped.progress()),
              bsg::testing::progress_without_timings(oracle.progress()))
        << name;
    EXPECT_EQ(read_text_file(stopped.returns()), read_text_file(oracle.returns())) << name;
    EXPECT_EQ(read_text_file(stopped.costs()), read_text_file(oracle.costs())) << name;
  }
}

// Issue 25, reproduction 3 (SIGKILL): the rerun reported the orphan as failed.
TEST(SweepKilled, TheRerunWaitsForChildrenStillRunningAndLogsTheirTrueState) {
  const TinySweep sweep;
  const fs::path out = sweep.temp.path() / "killed";
  const std::vector<fs::path> runs = sweep.run_dirs(out);
  const fs::path log = sweep.temp.path() / "first.log";
  const pid_t pid = start_and_wait_for_first_epochs(sweep, out, log);
  ASSERT_GT(pid, 0) << read_text_file(log);
  ASSERT_EQ(kill(pid, SIGKILL), 0);  // the sweep alone: its children run on
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);

  const auto rerun = run_bsg("sweep " + sweep.arguments(out));
  EXPECT_EQ(rerun.exit_code, 0) << rerun.output;
  const auto events = events_of(out);
  std::map<std::string, std::string> last;
  for (const auto& [event, run] : events) last[run] = event;
  for (const fs::path& run : runs) {
    const std::string name = fs::relative(run, out).generic_string();
    EXPECT_EQ(bsg::experiments::run_state(bsg::algos::RunDirectory(run)), bsg::experiments::RunState::finished) << name;
    EXPECT_EQ(last[name], "done") << name << "\n" << read_text_file(out / bsg::experiments::kSweepEventsName);
    EXPECT_EQ(count(events, "failed", name), 0u) << name;
    // Finished once: by the orphan (then no resume) or by the rerun after it.
    EXPECT_EQ(bsg::testing::progress_rows(bsg::algos::RunDirectory(run).progress()), 30) << name;
  }
  EXPECT_NE(rerun.output.find("waiting SafetyBallCircle-v0/trpo/default/seed="), std::string::npos) << rerun.output;
}

// Issue 25, reproduction 4: two sweeps at once on one directory.
TEST(SweepLock, ASecondSweepOnADirectoryInUseNamesTheFirstAndExits) {
  const TinySweep sweep;
  const fs::path out = sweep.temp.path() / "shared";
  const std::vector<fs::path> runs = sweep.run_dirs(out);
  const fs::path log = sweep.temp.path() / "first.log";
  const pid_t pid = start_and_wait_for_first_epochs(sweep, out, log);
  ASSERT_GT(pid, 0) << read_text_file(log);
  const auto second = run_bsg("sweep " + sweep.arguments(out));
  EXPECT_EQ(second.exit_code, 1) << second.output;
  EXPECT_NE(second.output.find("bsg: error: another bsg sweep (pid " + std::to_string(pid) + ") is using " +
                               out.string() + " (it holds " + (out / "sweep.lock").string() + ")"),
            std::string::npos)
      << second.output;
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  EXPECT_EQ(exit_code_of(status), 0) << read_text_file(log);
  for (const fs::path& run : runs) {
    EXPECT_EQ(bsg::experiments::run_state(bsg::algos::RunDirectory(run)), bsg::experiments::RunState::finished) << run;
    EXPECT_EQ(bsg::testing::progress_rows(bsg::algos::RunDirectory(run).progress()), 30) << run;
  }
}

}  // namespace
