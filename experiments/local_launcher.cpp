#include "experiments/local_launcher.h"

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <iostream>
#include <cstring>
#include <map>
#include <thread>

#include "algos/training/progress_line.h"
#include "algos/training/run_directory.h"
#include "common/csv_text.h"
#include "experiments/child_process.h"
#include "experiments/run_lock.h"
#include "experiments/sweep_events.h"
#include "experiments/sweep_manifest.h"
#include "experiments/sweep_progress.h"

namespace bsg::experiments {

namespace {

using Clock = std::chrono::steady_clock;

// The child command of one run: `bsg train RUN_FILE --out DIR` for a new run,
// `bsg train --resume DIR` for an unfinished one, under `mpirun -np K` if K > 1.
// The run file is fully resolved; --configs only spares `bsg train` the
// search for a configs/ directory above the run directory.
ChildCommand train_command(const PlannedRun& run, const std::filesystem::path& bsg_program,
                           const std::filesystem::path& configs_dir, int ranks_per_run) {
  ChildCommand command;
  if (ranks_per_run > 1) {
    command.argv = {"mpirun", "-np", std::to_string(ranks_per_run)};
    if (::geteuid() == 0) {
      command.argv.push_back("--oversubscribe");
      command.environment = {{"OMPI_ALLOW_RUN_AS_ROOT", "1"}, {"OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1"}};
    }
    // Ctrl-C reaches the ranks (they share our process group) and mpirun;
    // mpirun would SIGKILL them after 2 x odls_base_sigkill_timeout (1 s by
    // default), before they finish their epoch and checkpoint (cli/
    // stop_signals.h). The Slurm script raises it to 60 s as well.
    if (std::getenv("OMPI_MCA_odls_base_sigkill_timeout") == nullptr) {
      command.environment.emplace_back("OMPI_MCA_odls_base_sigkill_timeout", "60");
    }
  }
  command.argv.push_back(bsg_program.string());
  command.argv.push_back("train");
  if (run.state == RunState::resumable) {
    command.argv.insert(command.argv.end(), {"--resume", run.dir.string()});
  } else {
    command.argv.insert(command.argv.end(),
                        {(run.dir / kSweepRunFileName).string(), "--out", run.dir.string(), "--configs",
                         configs_dir.string()});
  }
  command.log_file = run.dir / kSweepRunLogName;
  return command;
}

// Leftovers of a start killed before its first checkpoint would make
// `bsg train` refuse the directory; a fresh start owns it.
void clear_unstarted_run(const algos::RunDirectory& directory) {
  std::error_code error;
  std::filesystem::remove(directory.progress(), error);
  std::filesystem::remove(directory.config(), error);
}

class SweepRunner {
 public:
  SweepRunner(SweepPlan plan, const LocalLaunchOptions& options, std::filesystem::path out_dir)
      : plan_(std::move(plan)),
        options_(options),
        out_dir_(std::move(out_dir)),
        configs_dir_(std::filesystem::absolute(options.configs_dir)),
        bsg_program_(options.bsg_program),
        events_(out_dir_),
        interactive_(::isatty(STDERR_FILENO) != 0) {}

  int run();

 private:
  struct Running {
    std::size_t index;
    Clock::time_point started;
  };

  void start(std::size_t index);
  void finish(const ChildExit& exit);
  void reconcile_earlier_sweep(std::vector<std::size_t>& queue);
  void wait_for(std::size_t index);
  void check_waiting(std::vector<std::size_t>& queue, std::size_t& next);
  void forward_stop_signal();
  int stopped_summary() const;
  void show_progress(bool force);
  double steps_done_now() const;

  SweepPlan plan_;
  LocalLaunchOptions options_;
  std::filesystem::path out_dir_;
  std::filesystem::path configs_dir_;
  std::filesystem::path bsg_program_;
  SweepEventLog events_;
  bool interactive_;
  std::map<pid_t, Running> running_;
  std::vector<std::size_t> waiting_;  // runs whose lock another process holds
  std::vector<std::size_t> failed_;
  std::vector<std::size_t> stopped_;  // stopped by a forwarded stop signal (exit 75)
  int stop_signal_ = 0;
  std::size_t not_started_ = 0;  // left in the queue by a stop signal
  Clock::time_point last_waiting_check_{};
  std::size_t finished_ = 0;
  double steps_done_at_start_ = 0;
  double steps_total_ = 0;
  Clock::time_point started_ = Clock::now();
  Clock::time_point last_shown_{};
};

// Env steps done: all of a finished run's, the logged epochs of a running
// one (read now), and for the others what the plan found.
double SweepRunner::steps_done_now() const {
  double done = 0;
  for (const PlannedRun& run : plan_.runs) done += static_cast<double>(run.steps_logged());
  for (const auto& [pid, running] : running_) {
    const PlannedRun& run = plan_.runs[running.index];
    const int epochs = std::min(logged_epochs(algos::RunDirectory(run.dir)), run.config.epochs);
    done += static_cast<double>(epochs) * run.config.steps_per_epoch - static_cast<double>(run.steps_logged());
  }
  return done;
}

void SweepRunner::start(std::size_t index) {
  PlannedRun& run = plan_.runs[index];
  std::filesystem::create_directories(run.dir);
  const std::optional<RunLock> lock = RunLock::try_acquire(run.dir);
  if (!lock) {
    wait_for(index);
    return;
  }
  const algos::RunDirectory directory(run.dir);
  run.state = run_state(directory);
  if (run.state == RunState::finished) {  // finished since the plan was made
    ++finished_;
    events_.record("skip", run.run.relative_dir(), "finished by another process");
    return;
  }
  if (run.state == RunState::fresh) clear_unstarted_run(directory);
  prepare_run_directory(run);
  ChildCommand command = train_command(run, bsg_program_, configs_dir_, options_.ranks_per_run);
  command.inherited_fd = lock->fd();  // the child holds the lock until it ends
  {
    std::ofstream log(command.log_file, std::ios::app);
    log << "=== bsg sweep " << sweep_timestamp() << ": " << command_line_text(command.argv) << "\n";
  }
  const pid_t pid = start_child(command);
  lock->record_holder(pid);
  running_[pid] = Running{index, Clock::now()};
  events_.record(run.state == RunState::resumable ? "resume" : "start", run.run.relative_dir(),
                 command_line_text(command.argv));
  if (!interactive_) {
    std::cerr << (run.state == RunState::resumable ? "resume " : "start  ") << run.run.relative_dir().string()
              << "\n";
  }
}

void SweepRunner::finish(const ChildExit& exit) {
  const auto found = running_.find(exit.pid);
  if (found == running_.end()) return;  // not ours (e.g. a grandchild reparented)
  const std::size_t index = found->second.index;
  PlannedRun& run = plan_.runs[index];
  const double seconds = std::chrono::duration<double>(Clock::now() - found->second.started).count();
  running_.erase(found);
  run.state = run_state(algos::RunDirectory(run.dir));
  const std::filesystem::path log = run.dir / kSweepRunLogName;
  if (exit.exit_code == 0 && run.state == RunState::finished) {
    ++finished_;
    events_.record("done", run.run.relative_dir(), algos::format_duration(seconds));
    if (!interactive_) {
      std::cerr << "done   " << run.run.relative_dir().string() << " (" << algos::format_duration(seconds) << ")\n";
    }
    return;
  }
  if (exit.exit_code == kSweepExitStopped && run.state == RunState::resumable) {
    stopped_.push_back(index);
    const std::string detail = "stop signal: checkpoint after " +
                               std::to_string(std::min(logged_epochs(algos::RunDirectory(run.dir)), run.config.epochs)) +
                               " of " + std::to_string(run.config.epochs) + " epochs";
    events_.record("stopped", run.run.relative_dir(), detail);
    if (interactive_) std::cerr << "\r\033[K";
    std::cerr << "stopped " << run.run.relative_dir().string() << " (" << detail << ")\n";
    return;
  }
  failed_.push_back(index);
  const std::string why = exit.exit_code == 0 ? "exit code 0 but no " + algos::RunDirectory(run.dir).evaluation().filename().string()
                                              : describe(exit);
  events_.record("failed", run.run.relative_dir(), why);
  if (interactive_) std::cerr << "\r\033[K";
  std::cerr << "FAILED " << run.run.relative_dir().string() << ": " << why << "; log: " << log.string() << "\n";
}

void SweepRunner::show_progress(bool force) {
  const Clock::time_point now = Clock::now();
  if (!force && now - last_shown_ < std::chrono::seconds(interactive_ ? 1 : 30)) return;
  last_shown_ = now;
  const double done = steps_done_now();
  const double elapsed = std::chrono::duration<double>(now - started_).count();
  const SweepCounts counts{plan_.runs.size(), finished_, running_.size() + waiting_.size(), failed_.size()};
  const std::string line =
      progress_line(counts, estimate_seconds_left(done - steps_done_at_start_, elapsed, steps_total_ - done));
  if (interactive_) {
    std::cerr << "\r\033[K" << line << std::flush;
  } else {
    std::cerr << line << "\n";
  }
}

// A run another process holds (its lock is taken): wait for it, do not fail it.
void SweepRunner::wait_for(std::size_t index) {
  const PlannedRun& run = plan_.runs[index];
  const std::filesystem::path lock = run.dir / kRunLockName;
  const std::string holder = describe_lock_holder(lock);
  waiting_.push_back(index);
  events_.record("waiting", run.run.relative_dir(), "still running in another process (" + holder + ", in " +
                                                        lock.string() + ")");
  if (interactive_) std::cerr << "\r\033[K";
  std::cerr << "waiting " << run.run.relative_dir().string() << ": another process (" << holder
            << ") still runs it, started by an earlier sweep; this sweep waits for it to end\n";
}

// Once a waited-for run's lock is free: done if that process finished it,
// else it joins the queue (started or resumed here).
void SweepRunner::check_waiting(std::vector<std::size_t>& queue, std::size_t& next) {
  if (waiting_.empty() || Clock::now() - last_waiting_check_ < std::chrono::seconds(1)) return;
  last_waiting_check_ = Clock::now();
  for (auto it = waiting_.begin(); it != waiting_.end();) {
    PlannedRun& run = plan_.runs[*it];
    if (!RunLock::try_acquire(run.dir)) {
      ++it;
      continue;
    }
    run.state = run_state(algos::RunDirectory(run.dir));
    if (run.state == RunState::finished) {
      ++finished_;
      events_.record("done", run.run.relative_dir(), "finished by the process this sweep waited for");
      std::cerr << "done   " << run.run.relative_dir().string() << " (by the process this sweep waited for)\n";
    } else {
      events_.record("interrupted", run.run.relative_dir(),
                     "the process this sweep waited for ended without finishing it");
      queue.insert(queue.begin() + static_cast<std::ptrdiff_t>(next), *it);
    }
    it = waiting_.erase(it);
  }
}

// Runs the log shows as started by an earlier sweep but never ended (that
// sweep was killed): record what became of them, so the log ends with each
// run's true state.
void SweepRunner::reconcile_earlier_sweep(std::vector<std::size_t>& queue) {
  const auto events = last_sweep_events(out_dir_);
  for (std::size_t index = 0; index < plan_.runs.size(); ++index) {
    PlannedRun& run = plan_.runs[index];
    const auto event = events.find(run.run.relative_dir());
    if (event == events.end()) continue;
    const std::string& last = event->second.first;
    if (last != "start" && last != "resume" && last != "waiting") continue;
    if (!RunLock::try_acquire(run.dir)) {
      std::erase(queue, index);
      wait_for(index);
      continue;
    }
    const bool queued = std::find(queue.begin(), queue.end(), index) != queue.end();
    run.state = run_state(algos::RunDirectory(run.dir));
    if (run.state == RunState::finished) {
      events_.record("done", run.run.relative_dir(), "finished after the sweep that started it ended");
      if (queued) {  // finished between the plan and now
        std::erase(queue, index);
        ++finished_;
      }
    } else {
      events_.record("interrupted", run.run.relative_dir(),
                     "the sweep that started it ended while it ran; " +
                         std::to_string(std::min(logged_epochs(algos::RunDirectory(run.dir)), run.config.epochs)) +
                         " epochs logged");
    }
  }
}

// As is to `bsg train`; SIGUSR1 to mpirun, the one signal it forwards to its ranks at once.
void SweepRunner::forward_stop_signal() {
  for (const auto& [pid, running] : running_) {
    ::kill(pid, options_.ranks_per_run > 1 ? SIGUSR1 : stop_signal_);
  }
}

int SweepRunner::stopped_summary() const {
  std::cerr << "bsg sweep: stopped by " << signal_name(stop_signal_) << ": " << stopped_.size()
            << " runs stopped with a checkpoint, " << not_started_ << " not started, " << finished_ << " of "
            << plan_.runs.size() << " finished";
  if (!failed_.empty()) std::cerr << ", " << failed_.size() << " failed";
  if (!waiting_.empty()) std::cerr << ", " << waiting_.size() << " still running in other processes";
  std::cerr << "; run the same bsg sweep command again to resume\n";
  for (const std::size_t index : failed_) {
    const PlannedRun& run = plan_.runs[index];
    std::cerr << "  failed: " << run.dir.string() << "  log: " << (run.dir / kSweepRunLogName).string() << "\n";
  }
  return kSweepExitStopped;
}

int SweepRunner::run() {
  std::vector<std::size_t> queue;
  for (std::size_t i = 0; i < plan_.runs.size(); ++i) {
    steps_total_ += static_cast<double>(plan_.runs[i].training_steps());
    if (plan_.runs[i].state == RunState::finished) {
      ++finished_;
    } else {
      queue.push_back(i);
    }
  }
  steps_done_at_start_ = steps_done_now();
  const int jobs = options_.jobs;
  std::cerr << "bsg sweep: " << plan_.runs.size() << " runs in " << out_dir_.string() << ": " << finished_
            << " already finished, " << queue.size() << " to run, " << jobs << " at a time"
            << (options_.ranks_per_run > 1 ? " with " + std::to_string(options_.ranks_per_run) + " ranks each" : "")
            << "\n";

  reconcile_earlier_sweep(queue);
  std::size_t next = 0;
  while (next < queue.size() || !running_.empty() || (!waiting_.empty() && stop_signal_ == 0)) {
    if (const int signal = options_.take_stop_signal(); signal != 0) {
      const bool first = stop_signal_ == 0;
      stop_signal_ = signal;
      if (interactive_) std::cerr << "\r\033[K";
      std::cerr << "bsg sweep: " << signal_name(signal) << " received" << (first ? "" : " again")
                << ": no new run starts; asking the " << running_.size()
                << " running runs to stop at the end of their epoch with a checkpoint, then waiting for them\n";
      forward_stop_signal();
    }
    while (stop_signal_ == 0 && next < queue.size() &&
           running_.size() + waiting_.size() < static_cast<std::size_t>(jobs)) {
      try {
        start(queue[next]);
      } catch (const std::exception& e) {
        const PlannedRun& run = plan_.runs[queue[next]];
        failed_.push_back(queue[next]);
        events_.record("failed", run.run.relative_dir(), e.what());
        std::cerr << "FAILED " << run.run.relative_dir().string() << ": " << e.what() << "\n";
      }
      ++next;
      if (interactive_) show_progress(true);
    }
    if (stop_signal_ != 0) {
      not_started_ += queue.size() - next;
      next = queue.size();
    }
    check_waiting(queue, next);
    bool reaped = false;
    while (const std::optional<ChildExit> exit = reap_exited_child()) {
      finish(*exit);
      reaped = true;
    }
    show_progress(reaped);
    if (!reaped) std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  if (interactive_) {
    show_progress(true);
    std::cerr << "\n";
  }
  if (stop_signal_ != 0) return stopped_summary();

  if (failed_.empty()) {
    std::cerr << "bsg sweep: all " << plan_.runs.size() << " runs finished; 'bsg table " << out_dir_.string()
              << "' selects and tabulates them\n";
    return 0;
  }
  std::cerr << "bsg sweep: " << failed_.size() << " of " << plan_.runs.size()
            << " runs failed (run the sweep again to retry them):\n";
  for (const std::size_t index : failed_) {
    const PlannedRun& run = plan_.runs[index];
    std::cerr << "  " << run.dir.string() << "  log: " << (run.dir / kSweepRunLogName).string() << "\n";
  }
  return 1;
}

}  // namespace

int run_sweep_locally(SweepPlan plan, const std::filesystem::path& sweep_dir,
                      const LocalLaunchOptions& options) {
  return SweepRunner(std::move(plan), options, sweep_dir).run();
}

}  // namespace bsg::experiments
