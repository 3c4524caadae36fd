// Guards an object whose methods release the GIL: a second Python thread that
// calls in while the first is still inside gets a RuntimeError instead of a
// data race (an Env is not thread-safe, env.h).
#pragma once

#include <atomic>
#include <stdexcept>
#include <string>

namespace bsg::python {

class ExclusiveUse {
 public:
  ExclusiveUse(std::atomic<bool>& busy, const std::string& what) : busy_(busy) {
    if (busy_.exchange(true, std::memory_order_acquire)) {
      throw std::runtime_error(what + " is in use by another thread; use one per thread");
    }
  }
  ~ExclusiveUse() { busy_.store(false, std::memory_order_release); }
  ExclusiveUse(const ExclusiveUse&) = delete;
  ExclusiveUse& operator=(const ExclusiveUse&) = delete;

 private:
  std::atomic<bool>& busy_;
};

}  // namespace bsg::python
