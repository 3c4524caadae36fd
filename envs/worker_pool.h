// The thread pool that steps the environments of a VectorEnv and of a
// MultiAgentVectorEnv: run(count, job) runs job(i) for every i in [0, count),
// the caller taking part, and returns when all have run. Which thread runs
// which index is not fixed; a caller whose jobs each touch only their own
// environment gets the same results whatever the number of threads.
#pragma once

#include <atomic>
#include <cstdint>
#include <exception>
#include <functional>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace bsg::envs {

// Indices are claimed one at a time from an atomic word holding (round, next
// index), and the caller waits for `count` completed jobs, not for every
// worker to check in: a worker the OS keeps off the CPU (the machine is
// shared) merely takes fewer environments, or none, and never holds up the
// round. Waiting is a short spin (a round is tens to hundreds of microseconds,
// a futex wake-up several) and then a blocking atomic wait.
class WorkerPool {
 public:
  // num_threads >= 1 counts the caller: num_threads - 1 threads are started.
  explicit WorkerPool(int num_threads);
  ~WorkerPool();
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  // Returns when every job has run; rethrows the first exception a job threw.
  // Not reentrant: one caller thread at a time.
  void run(int count, const std::function<void(int)>& job);

 private:
  void worker_loop();
  void work(std::uint32_t round);

  std::vector<std::thread> threads_;
  std::atomic<std::uint32_t> round_{0};
  std::atomic<bool> stopping_{false};
  std::atomic<std::uint64_t> claims_{0};  // (round << 32) | next index
  std::atomic<const std::function<void(int)>*> job_{nullptr};
  std::atomic<int> count_{0};
  std::atomic<int> completed_{0};
  std::mutex error_mutex_;
  std::exception_ptr error_;
};

// The number of threads for `num_envs` environments: num_threads, or the
// machine's hardware threads if it is 0, at most num_envs. Throws
// std::invalid_argument ("<owner>: num_threads must be >= 0 ...") if < 0.
int resolve_num_threads(int num_threads, int num_envs, const std::string& owner);

}  // namespace bsg::envs
