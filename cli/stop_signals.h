// SIGTERM, SIGINT, SIGHUP and SIGUSR1 as a request to stop at the next safe point
// instead of an immediate death: the constructor blocks these signals (before MPI starts
// its threads, which inherit the mask, so no thread can take the default
// action); a signal sent then stays pending, and stop_pending() reads it with
// sigpending() at the epoch boundary. No handler and no global flag: the
// kernel's pending set is the flag.
//
// SIGUSR1 because of Open MPI's mpirun (4.1): it forwards SIGUSR1 to every
// rank, but on SIGTERM or SIGINT it only sends SIGCONT, then SIGTERM after
// odls_base_sigkill_timeout seconds (default 1) and SIGKILL after as many
// again - too soon to finish an epoch unless that MCA parameter is raised.
//
// SIGHUP because closing a terminal sends it to the programs started there
// (a `bsg sweep` and the `bsg train` children it runs): they stop as on SIGTERM.
//
// `bsg train` builds one before anything else; the exit code of a run that
// stopped this way is kExitStoppedBySignal (its checkpoint and progress.csv
// are complete; `bsg train --resume DIR` continues it).
#pragma once

#include <signal.h>

namespace bsg::cli {

// EX_TEMPFAIL of sysexits.h: "try again later" - the run is unfinished but
// intact, unlike a run killed by a signal (128 + N) or failed (1).
inline constexpr int kExitStoppedBySignal = 75;

class StopSignals {
 public:
  StopSignals();
  // Restores the signal mask only if no stop signal is pending (unblocking a
  // pending SIGTERM would kill the process on the spot).
  ~StopSignals();
  StopSignals(const StopSignals&) = delete;
  StopSignals& operator=(const StopSignals&) = delete;

  // The pending stop signal (SIGTERM, SIGINT, SIGHUP or SIGUSR1), or 0.
  int stop_pending() const;
  // The same, taken out of the pending set (sigtimedwait), so that the next
  // call sees only a signal sent after this one.
  int take_pending() const;

 private:
  sigset_t previous_mask_;
};

}  // namespace bsg::cli
