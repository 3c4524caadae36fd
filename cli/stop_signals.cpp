#include "stop_signals.h"

#include <pthread.h>

#include <cstring>
#include <stdexcept>
#include <string>

namespace bsg::cli {

namespace {

sigset_t stop_set() {
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGTERM);
  sigaddset(&set, SIGINT);
  sigaddset(&set, SIGHUP);
  sigaddset(&set, SIGUSR1);
  return set;
}

}  // namespace

StopSignals::StopSignals() {
  const sigset_t set = stop_set();
  const int error = pthread_sigmask(SIG_BLOCK, &set, &previous_mask_);
  if (error != 0) {
    throw std::runtime_error(std::string("cannot block SIGTERM/SIGINT/SIGHUP/SIGUSR1: ") + std::strerror(error));
  }
}

StopSignals::~StopSignals() {
  if (stop_pending() == 0) pthread_sigmask(SIG_SETMASK, &previous_mask_, nullptr);
}

int StopSignals::stop_pending() const {
  sigset_t pending;
  sigemptyset(&pending);
  if (sigpending(&pending) != 0) return 0;
  if (sigismember(&pending, SIGTERM) == 1) return SIGTERM;
  if (sigismember(&pending, SIGINT) == 1) return SIGINT;
  if (sigismember(&pending, SIGHUP) == 1) return SIGHUP;
  if (sigismember(&pending, SIGUSR1) == 1) return SIGUSR1;
  return 0;
}

int StopSignals::take_pending() const {
  const sigset_t set = stop_set();
  const timespec no_wait{0, 0};
  const int signal = sigtimedwait(&set, nullptr, &no_wait);
  return signal > 0 ? signal : 0;
}

}  // namespace bsg::cli
