#include "envs/worker_pool.h"

#include <algorithm>
#include <stdexcept>

namespace bsg::envs {

namespace {

// Spins a microsecond or so, or until done() holds.
template <typename Predicate>
void spin_until(Predicate done) {
  constexpr int kSpinIterations = 200;  // short: on a shared machine spinning steals the core
  for (int i = 0; i < kSpinIterations && !done(); ++i) {
#if defined(__x86_64__) || defined(__i386__)
    __builtin_ia32_pause();
#endif
  }
}

}  // namespace

WorkerPool::WorkerPool(int num_threads) {
  for (int t = 1; t < num_threads; ++t) threads_.emplace_back([this] { worker_loop(); });
}

WorkerPool::~WorkerPool() {
  stopping_.store(true, std::memory_order_relaxed);
  round_.fetch_add(1, std::memory_order_release);
  round_.notify_all();
  for (std::thread& thread : threads_) thread.join();
}

void WorkerPool::run(int count, const std::function<void(int)>& job) {
  const std::uint32_t round = round_.load(std::memory_order_relaxed) + 1;
  job_.store(&job, std::memory_order_relaxed);
  count_.store(count, std::memory_order_relaxed);
  completed_.store(0, std::memory_order_relaxed);
  error_ = nullptr;
  claims_.store(std::uint64_t{round} << 32, std::memory_order_release);
  round_.store(round, std::memory_order_release);
  if (!threads_.empty()) round_.notify_all();
  work(round);
  for (;;) {
    spin_until([&] { return completed_.load(std::memory_order_acquire) == count; });
    const int completed = completed_.load(std::memory_order_acquire);
    if (completed == count) break;
    completed_.wait(completed, std::memory_order_acquire);
  }
  if (error_) std::rethrow_exception(error_);
}

void WorkerPool::worker_loop() {
  std::uint32_t seen = 0;
  for (;;) {
    for (;;) {
      spin_until([&] { return round_.load(std::memory_order_acquire) != seen; });
      const std::uint32_t now = round_.load(std::memory_order_acquire);
      if (now != seen) {
        seen = now;
        break;
      }
      round_.wait(seen, std::memory_order_acquire);
    }
    if (stopping_.load(std::memory_order_relaxed)) return;
    work(seen);
  }
}

// Claims and runs jobs of `round` until none is left. A claim succeeds only
// while `round` is current, so a late worker never runs a stale job, and the
// round cannot end (completed_ == count) before a claimed job has run.
void WorkerPool::work(std::uint32_t round) {
  std::uint64_t claims = claims_.load(std::memory_order_acquire);
  for (;;) {
    const auto claim_round = static_cast<std::uint32_t>(claims >> 32);
    const auto index = static_cast<int>(claims & 0xffffffffu);
    const int count = count_.load(std::memory_order_relaxed);
    if (claim_round != round || index >= count) return;
    if (!claims_.compare_exchange_weak(claims, claims + 1, std::memory_order_acquire)) continue;
    try {
      (*job_.load(std::memory_order_relaxed))(index);
    } catch (...) {
      const std::lock_guard<std::mutex> lock(error_mutex_);
      if (!error_) error_ = std::current_exception();
    }
    if (completed_.fetch_add(1, std::memory_order_acq_rel) + 1 == count) {
      completed_.notify_one();
    }
    claims = claims_.load(std::memory_order_acquire);
  }
}

int resolve_num_threads(int num_threads, int num_envs, const std::string& owner) {
  if (num_threads < 0) {
    throw std::invalid_argument(owner + ": num_threads must be >= 0 (0: one per hardware "
                                "thread), got " + std::to_string(num_threads));
  }
  if (num_threads == 0) {
    num_threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  }
  return std::min(num_threads, num_envs);
}

}  // namespace bsg::envs
