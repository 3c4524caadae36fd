// `bsg sweep` end to end on configs/grids/quick.yaml: a sweep killed mid-way
// (SIGKILL to its process group, children included) and started again
// finishes every run exactly once - finished runs are not rerun, unfinished
// ones resume from their checkpoints and log each epoch once - and then
// `bsg table` and scripts/plot_curves.py produce the table and the plots.
// Also the dry run, and errors naming the grid, the key or the run at fault.
#include <gtest/gtest.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
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
#include "common/run_config_yaml.h"
#include "experiments/grid_expansion.h"
#include "experiments/run_results.h"
#include "experiments/sweep_manifest.h"
#include "run_bsg.h"
#include "sweep_processes.h"

namespace fs = std::filesystem;
using bsg::testing::read_text_file;
using bsg::testing::run_bsg;
using bsg::testing::TemporaryDirectory;
using bsg::testing::live_processes_in_group;
using bsg::testing::start_sweep_in_own_group;

namespace {

using bsg::testing::kSource;
const fs::path kQuickGrid = kSource / "configs" / "grids" / "quick.yaml";

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream stream(text);
  std::string line;
  while (std::getline(stream, line)) {
    if (!line.empty()) lines.push_back(line);
  }
  return lines;
}

// Runs of the quick grid as the sweep names them.
std::vector<fs::path> quick_run_dirs(const fs::path& out) {
  std::vector<fs::path> dirs;
  for (const bsg::experiments::GridRun& run : bsg::experiments::expand_grid(bsg::experiments::load_grid_file(kQuickGrid))) {
    dirs.push_back(out / run.relative_dir());
  }
  return dirs;
}

// The epoch column of a progress.csv.
std::vector<std::string> logged_epoch_values(const fs::path& progress) {
  std::vector<std::string> epochs;
  const std::vector<std::string> lines = lines_of(read_text_file(progress));
  for (std::size_t i = 1; i < lines.size(); ++i) epochs.push_back(bsg::parse_csv_fields(lines[i]).at(0));
  return epochs;
}

// (event, run_dir) of sweep_events.csv from line `first` on.
std::vector<std::pair<std::string, std::string>> events_from(const fs::path& out, std::size_t first) {
  std::vector<std::pair<std::string, std::string>> events;
  const std::vector<std::string> lines = lines_of(read_text_file(out / bsg::experiments::kSweepEventsName));
  for (std::size_t i = std::max<std::size_t>(first, 1); i < lines.size(); ++i) {
    const std::vector<std::string> fields = bsg::parse_csv_fields(lines[i]);
    events.emplace_back(fields.at(1), fields.at(2));
  }
  return events;
}

std::size_t count_events(const std::vector<std::pair<std::string, std::string>>& events,
                         const std::string& event, const std::string& run_dir) {
  std::size_t count = 0;
  for (const auto& [name, dir] : events) count += name == event && dir == run_dir ? 1 : 0;
  return count;
}

// A grid of one short TRPO run (SafetyBallCircle-v0, seed 7, one epoch of 500
// steps) in a scratch directory, the sweep's output directory, and that run's
// directory in it, created empty.
struct OneRunSweep {
  OneRunSweep() { fs::create_directories(run_dir); }

  // `bsg sweep` of the grid into `out` with the shipped configs.
  std::string command() const {
    return "sweep " + grid.string() + " --configs " + (kSource / "configs").string() + " --out " +
           out.string();
  }

  static fs::path write_grid(const fs::path& path) {
    std::ofstream(path)
        << "envs: [SafetyBallCircle-v0]\nseeds: [7]\nfixed: {epochs: 1, steps_per_epoch: 500}\n"
           "algorithms: {trpo: }\n";
    return path;
  }

  TemporaryDirectory temp;
  fs::path grid = write_grid(temp.path() / "one.yaml");
  fs::path out = temp.path() / "out";
  bsg::experiments::GridRun run = bsg::experiments::expand_grid(bsg::experiments::load_grid_file(grid)).front();
  fs::path run_dir = out / run.relative_dir();
};

TEST(Sweep, KilledMidwayAndResumedFinishesEveryRunExactlyOnceThenTablesAndPlots) {
  TemporaryDirectory temp;
  const fs::path out = temp.path() / "quick";
  const std::vector<fs::path> runs = quick_run_dirs(out);
  ASSERT_EQ(runs.size(), 4u);

  // 1. Start, and kill the whole process group once one run has finished
  //    while another is part-way through.
  const pid_t sweep = start_sweep_in_own_group(kQuickGrid.string() + " --jobs 2 --out " + out.string(),
                                               temp.path() / "first.log");
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  bool midway = false;
  int status = 0;
  while (!midway && std::chrono::steady_clock::now() < deadline) {
    if (waitpid(sweep, &status, WNOHANG) == sweep) {
      FAIL() << "the sweep ended before it could be killed mid-way:\n"
             << read_text_file(temp.path() / "first.log");
    }
    bool some_finished = false;
    bool some_partial = false;
    for (const fs::path& run : runs) {
      const bsg::algos::RunDirectory directory(run);
      const bsg::experiments::RunState state = bsg::experiments::run_state(directory);
      some_finished |= state == bsg::experiments::RunState::finished;
      some_partial |= state == bsg::experiments::RunState::resumable && bsg::experiments::logged_epochs(directory) >= 1;
    }
    midway = some_finished && some_partial;
    if (!midway) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ASSERT_TRUE(midway) << "no mid-way state within 60 s:\n"
                      << read_text_file(temp.path() / "first.log");
  ASSERT_EQ(kill(-sweep, SIGKILL), 0);
  ASSERT_EQ(waitpid(sweep, &status, 0), sweep);
  ASSERT_TRUE(WIFSIGNALED(status));
  // The killed `bsg train` children are not ours to wait for; until the kernel
  // has ended each of them it may still hold its run's lock, and a sweep started
  // in that moment rightly refuses the run. Wait until the group is empty.
  const auto group_deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (live_processes_in_group(sweep) > 0 && std::chrono::steady_clock::now() < group_deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ASSERT_EQ(live_processes_in_group(sweep), 0) << "processes of the killed sweep still run after 30 s";

  std::map<fs::path, bsg::experiments::RunState> state_at_kill;
  std::size_t unfinished = 0;
  std::size_t resumable = 0;
  for (const fs::path& run : runs) {
    state_at_kill[run] = bsg::experiments::run_state(bsg::algos::RunDirectory(run));
    unfinished += state_at_kill[run] != bsg::experiments::RunState::finished ? 1 : 0;
    resumable += state_at_kill[run] == bsg::experiments::RunState::resumable ? 1 : 0;
  }
  ASSERT_GE(resumable, 1u) << "the kill should leave a run part-way through";
  const std::size_t events_before = lines_of(read_text_file(out / bsg::experiments::kSweepEventsName)).size();

  // 2. Start again: it finishes the rest.
  const auto second = run_bsg("sweep " + kQuickGrid.string() + " --jobs 2 --out " + out.string());
  ASSERT_EQ(second.exit_code, 0) << second.output;
  EXPECT_NE(second.output.find(std::to_string(4 - unfinished) + " already finished"), std::string::npos)
      << second.output;

  const auto events = events_from(out, events_before);
  for (const fs::path& run : runs) {
    const std::string name = fs::relative(run, out).generic_string();
    const bsg::algos::RunDirectory directory(run);
    ASSERT_EQ(bsg::experiments::run_state(directory), bsg::experiments::RunState::finished) << name;
    // Each epoch logged once, in order; the evaluation written once.
    EXPECT_EQ(logged_epoch_values(directory.progress()),
              (std::vector<std::string>{"0", "1", "2", "3", "4", "5"}))
        << name;
    EXPECT_EQ(lines_of(read_text_file(directory.returns())).size(), 2u) << name;
    // The resolved run file reproduces the run's configuration.
    EXPECT_EQ(bsg::load_resolved_run_config(run / bsg::experiments::kSweepRunFileName).seed,
              bsg::load_resolved_run_config(directory.config()).seed);
    switch (state_at_kill[run]) {
      case bsg::experiments::RunState::finished:  // not touched again
        EXPECT_EQ(count_events(events, "start", name) + count_events(events, "resume", name), 0u) << name;
        break;
      case bsg::experiments::RunState::resumable:  // continued from its checkpoint, not restarted
        EXPECT_EQ(count_events(events, "resume", name), 1u) << name;
        EXPECT_EQ(count_events(events, "start", name), 0u) << name;
        EXPECT_EQ(count_events(events, "done", name), 1u) << name;
        break;
      case bsg::experiments::RunState::fresh:
        EXPECT_EQ(count_events(events, "start", name), 1u) << name;
        EXPECT_EQ(count_events(events, "done", name), 1u) << name;
        break;
    }
  }

  // 3. A third start has nothing to do.
  const std::size_t events_before_third =
      lines_of(read_text_file(out / bsg::experiments::kSweepEventsName)).size();
  const auto third = run_bsg("sweep " + kQuickGrid.string() + " --out " + out.string());
  EXPECT_EQ(third.exit_code, 0) << third.output;
  EXPECT_NE(third.output.find("4 already finished, 0 to run"), std::string::npos) << third.output;
  EXPECT_EQ(lines_of(read_text_file(out / bsg::experiments::kSweepEventsName)).size(), events_before_third);

  // 4. Table 1 and the learning curves.
  const auto table = run_bsg("table " + out.string());
  ASSERT_EQ(table.exit_code, 0) << table.output;
  EXPECT_NE(table.output.find("| Env | TRPO | TRPO-L |"), std::string::npos) << table.output;
  EXPECT_NE(table.output.find("| BallCircle | 1.00 ("), std::string::npos) << table.output;
  EXPECT_EQ(table.output.find("missing |"), std::string::npos) << table.output;
  for (const char* file : {"table1.md", "table1.csv", "table1.tex", "configurations.csv"}) {
    EXPECT_TRUE(fs::is_regular_file(out / file)) << file;
  }

  const std::string plot_command =
      (kSource / "scripts" / "plot_curves.py").string() + " " + out.string() + " 2>&1";
  FILE* pipe = popen(plot_command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string plot_output;
  char chunk[512];
  while (fgets(chunk, sizeof chunk, pipe) != nullptr) plot_output += chunk;
  EXPECT_EQ(pclose(pipe), 0) << plot_output;
  const fs::path png = out / "plots" / "SafetyBallCircle-v0.png";
  ASSERT_TRUE(fs::is_regular_file(png)) << plot_output;
  EXPECT_EQ(read_text_file(png).substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  EXPECT_NE(plot_output.find("(2 curves)"), std::string::npos) << plot_output;
}

TEST(Sweep, DryRunListsTheRunsAndTheirCostWithoutRunningAnything) {
  TemporaryDirectory temp;
  const auto result = run_bsg("sweep " + kQuickGrid.string() + " --dry-run --out " + (temp.path() / "q").string());
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("SafetyBallCircle-v0/lag-trpo/target_kl=0.01/seed=1"), std::string::npos)
      << result.output;
  EXPECT_NE(result.output.find("4 runs of 2 configurations: 0 finished, 0 to resume, 4 new"),
            std::string::npos)
      << result.output;
  // 4 runs x 6 epochs x 1000 steps.
  EXPECT_NE(result.output.find("24 000 env steps of training in all"), std::string::npos) << result.output;
  EXPECT_FALSE(fs::exists(temp.path() / "q"));
}

TEST(Sweep, TheReportGridCostsWhatTable3AndTheAppendixSay) {
  const auto result = run_bsg("sweep " + (kSource / "configs" / "grids" / "report.yaml").string() +
                              " --dry-run --env SafetyBallRun-v0 --alg trpo --out /tmp/bsg_never_created");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  // 2 configurations x 4 seeds x 100 epochs x 32 000 steps.
  EXPECT_NE(result.output.find("8 runs of 2 configurations"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("25 600 000 env steps of training in all"), std::string::npos) << result.output;
}

TEST(Sweep, AnOfflineGridCostsGradientUpdatesAndNoEnvStep) {
  const auto result = run_bsg("sweep " + (kSource / "configs" / "benchmarks" / "offline_small.yaml").string() +
                              " --dry-run --out /tmp/bsg_never_created");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  // 5 learners x 6 datasets x 3 seeds, each 40 epochs x 200 updates.
  EXPECT_NE(result.output.find("90 runs of 30 configurations"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("8 000 upd  /tmp/bsg_never_created/SafetyCarRun-v0/cpq/default/seed=2"),
            std::string::npos)
      << result.output;
  EXPECT_NE(result.output.find("cost: 0 env steps of training in all"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("720 000 gradient updates in all, 720 000 still to run"), std::string::npos)
      << result.output;
}

TEST(Sweep, AnUnknownKeyInTheGridIsNamedWithItsLine) {
  TemporaryDirectory temp;
  const fs::path grid = temp.path() / "bad.yaml";
  std::ofstream(grid) << "envs: [SafetyBallCircle-v0]\nseeds: [0]\nalgorithms:\n  trpo:\n    axes:\n"
                         "      target_kll: [0.01]\n";
  const auto result = run_bsg("sweep " + grid.string() + " --configs " + (kSource / "configs").string());
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_NE(result.output.find(grid.string() + ":6:7: unknown configuration key 'target_kll'"), std::string::npos)
      << result.output;
}

TEST(Sweep, MissingAndMalformedGridFilesAreNamed) {
  TemporaryDirectory temp;
  auto result = run_bsg("sweep " + (temp.path() / "none.yaml").string() + " --configs " +
                        (kSource / "configs").string());
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_NE(result.output.find("grid file not found: " + (temp.path() / "none.yaml").string()), std::string::npos)
      << result.output;

  const fs::path grid = temp.path() / "broken.yaml";
  std::ofstream(grid) << "envs: [SafetyBallCircle-v0\nseeds: [0]\n";
  result = run_bsg("sweep " + grid.string() + " --configs " + (kSource / "configs").string());
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_NE(result.output.find(grid.string() + ": malformed YAML"), std::string::npos) << result.output;
}

TEST(Sweep, RanksThatDoNotDivideTheBatchAreRejectedNamingTheRun) {
  const auto result = run_bsg("sweep " + kQuickGrid.string() + " --dry-run --ranks-per-run 3");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_NE(result.output.find("run SafetyBallCircle-v0/trpo/target_kl=0.01/seed=0 with --ranks-per-run 3"),
            std::string::npos)
      << result.output;
}

TEST(Sweep, AFailedRunIsReportedWithItsLogAndTheExitCodeSaysSo) {
  // A run directory with this run's configuration but a damaged checkpoint:
  // the sweep resumes it, and `bsg train --resume` fails.
  const OneRunSweep sweep;
  const fs::path& run_dir = sweep.run_dir;
  bsg::RunConfig config =
      bsg::experiments::resolve_grid_run(sweep.run, kSource / "configs", sweep.grid.string());
  bsg::write_run_config(config, bsg::algos::RunDirectory(run_dir).config());
  std::ofstream(bsg::algos::RunDirectory(run_dir).checkpoint()) << "not a checkpoint";

  const auto result = run_bsg(sweep.command());
  EXPECT_EQ(result.exit_code, 1) << result.output;
  EXPECT_NE(result.output.find("FAILED SafetyBallCircle-v0/trpo/default/seed=7: exit code 1; log: " +
                               (run_dir / bsg::experiments::kSweepRunLogName).string()),
            std::string::npos)
      << result.output;
  EXPECT_NE(result.output.find("1 of 1 runs failed"), std::string::npos) << result.output;
  EXPECT_NE(read_text_file(run_dir / bsg::experiments::kSweepRunLogName).find("checkpoint"), std::string::npos);
}

TEST(Sweep, RunsWithoutEvaluationEpisodesFinishAndTheTableCountsThemMissing) {
  // eval_episodes: 0 (learning curves only): the run ends with an
  // evaluation.json of 0 episodes, the sweep and --status see it finished,
  // and Table 1 has no J or H for it.
  TemporaryDirectory temp;
  const fs::path grid = temp.path() / "curves.yaml";
  std::ofstream(grid) << "envs: [SafetyBallCircle-v0]\nseeds: [7]\n"
                         "fixed: {epochs: 1, steps_per_epoch: 500, eval_episodes: 0}\nalgorithms: {trpo: }\n";
  const fs::path out = temp.path() / "out";
  const std::string sweep = "sweep " + grid.string() + " --configs " + (kSource / "configs").string() +
                            " --out " + out.string();
  const auto first = run_bsg(sweep);
  ASSERT_EQ(first.exit_code, 0) << first.output;
  const fs::path run_dir = out / "SafetyBallCircle-v0" / "trpo" / "default" / "seed=7";
  const std::string evaluation = read_text_file(bsg::algos::RunDirectory(run_dir).evaluation());
  EXPECT_NE(evaluation.find("\"episodes\": 0"), std::string::npos) << evaluation;
  EXPECT_NE(evaluation.find("\"mean_return\": null"), std::string::npos) << evaluation;
  EXPECT_EQ(bsg::experiments::logged_epochs(bsg::algos::RunDirectory(run_dir)), 1);

  const auto again = run_bsg(sweep);
  EXPECT_EQ(again.exit_code, 0) << again.output;
  EXPECT_NE(again.output.find("1 already finished"), std::string::npos) << again.output;
  const auto status = run_bsg("sweep --status " + out.string());
  EXPECT_EQ(status.exit_code, 0) << status.output;
  EXPECT_NE(status.output.find("finished"), std::string::npos) << status.output;
  const auto table = run_bsg("table " + out.string());
  EXPECT_EQ(table.exit_code, 0) << table.output;
  EXPECT_NE(read_text_file(out / "table1.md").find("missing"), std::string::npos) << read_text_file(out / "table1.md");
}

TEST(Sweep, AnOfflineGridNamingADatasetDirectoryRunsAndIsFoundFinishedAgain) {
  // config.yaml records the file the run learned from; the grid names the directory that holds it
  // one level down. The sweep run again must see the same configuration, finished.
  TemporaryDirectory temp;
  const fs::path data = temp.path() / "datasets";
  const std::string file = (data / "recipe" / "SafetyBallCircle-v0.hdf5").string();
  fs::create_directories(data / "recipe");
  const auto collect = run_bsg("collect --out " + file + " --env SafetyBallCircle-v0 --policy random --episodes 2 --seed 0");
  ASSERT_EQ(collect.exit_code, 0) << collect.output;
  const fs::path grid = temp.path() / "offline.yaml";
  std::ofstream(grid) << "envs: [SafetyBallCircle-v0]\nseeds: [0]\n"
                         "fixed: {dataset: " << data.string() << ", epochs: 1, updates_per_epoch: 2, eval_every: 1, "
                         "eval_episodes: 1, hidden_sizes: [8], batch_size: 16}\nalgorithms: {bc-all: }\n";
  const fs::path out = temp.path() / "out";
  const std::string sweep = "sweep " + grid.string() + " --configs " + (kSource / "configs").string() +
                            " --out " + out.string();
  const auto first = run_bsg(sweep);
  ASSERT_EQ(first.exit_code, 0) << first.output;
  const fs::path run_dir = out / "SafetyBallCircle-v0" / "bc-all" / "default" / "seed=0";
  const std::string config = read_text_file(bsg::algos::RunDirectory(run_dir).config());
  EXPECT_NE(config.find("dataset: " + file), std::string::npos) << config;
  const auto again = run_bsg(sweep);
  EXPECT_EQ(again.exit_code, 0) << again.output;
  EXPECT_NE(again.output.find("1 already finished"), std::string::npos) << again.output;
}

TEST(Sweep, ARunDirectoryOfAnotherConfigurationIsNotTouched) {
  const OneRunSweep sweep;
  bsg::RunConfig config =
      bsg::experiments::resolve_grid_run(sweep.run, kSource / "configs", sweep.grid.string());
  config.epochs = 2;
  bsg::write_run_config(config, bsg::algos::RunDirectory(sweep.run_dir).config());

  const auto result = run_bsg(sweep.command());
  EXPECT_EQ(result.exit_code, 1) << result.output;
  EXPECT_NE(result.output.find("holds a run of another configuration"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("epochs: 2"), std::string::npos) << result.output;
}

// Issue 25, reproduction 3: a rerun reported a run that a killed sweep's
// orphan still ran as failed and exited 1. It now waits for it.
TEST(Sweep, ARunLockedByAnotherProcessIsWaitedForNotStartedTwice) {
  const OneRunSweep sweep;
  const fs::path& run_dir = sweep.run_dir;
  // As a `bsg train` left running by a killed sweep would hold it (not
  // inherited by the sweep this test starts).
  const int fd = open((run_dir / "train.lock").c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(flock(fd, LOCK_EX | LOCK_NB), 0);
  const std::string holder = std::to_string(getpid());
  ASSERT_EQ(pwrite(fd, holder.data(), holder.size(), 0), static_cast<ssize_t>(holder.size()));
  const fs::path log = sweep.temp.path() / "sweep.log";
  const pid_t pid = start_sweep_in_own_group(sweep.command().substr(std::string("sweep ").size()), log);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (read_text_file(log).find("waiting") == std::string::npos && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  EXPECT_NE(read_text_file(log).find("waiting SafetyBallCircle-v0/trpo/default/seed=7: another process (pid " +
                                     holder + ") still runs it"),
            std::string::npos)
      << read_text_file(log);
  EXPECT_FALSE(fs::exists(bsg::algos::RunDirectory(run_dir).progress())) << "not started while the lock is held";
  close(fd);  // that process has ended, unfinished: the sweep starts the run
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << read_text_file(log);
  const auto events = events_from(sweep.out, 0);
  const std::string name = sweep.run.relative_dir().generic_string();
  ASSERT_EQ(events.size(), 4u) << read_text_file(sweep.out / bsg::experiments::kSweepEventsName);
  EXPECT_EQ(events[0], std::make_pair(std::string("waiting"), name));
  EXPECT_EQ(events[1], std::make_pair(std::string("interrupted"), name));
  EXPECT_EQ(events[2], std::make_pair(std::string("start"), name));
  EXPECT_EQ(events[3], std::make_pair(std::string("done"), name));
}

}  // namespace
