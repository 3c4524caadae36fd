// Issue 3: "no allocation on the step path". Once an environment has been
// reset and has stepped through its first episode (Bullet sizes its pair
// cache, manifold pools and solver arrays then; later high-water marks of
// contact pairs are served by the block pool, envs/bullet_block_pool.h),
// Env::step allocates nothing:
// heap allocations are counted by interposing malloc, calloc and realloc
// (glibc only; not under AddressSanitizer, which owns malloc). Bullet's
// btAlignedAlloc and operator new both end in malloc, so they are counted too.
// Resets are not on the step path and are not counted.
#include <gtest/gtest.h>

#include <atomic>
#include <cstddef>
#include <string>
#include <vector>

#include "common/random.h"
#include "envs/env.h"

#if defined(__GLIBC__) && !defined(__SANITIZE_ADDRESS__)
#define BSG_COUNT_MALLOC 1
namespace {
std::atomic<long> heap_calls{0};
}
extern "C" void* __libc_malloc(std::size_t size);
extern "C" void* __libc_calloc(std::size_t count, std::size_t size);
extern "C" void* __libc_realloc(void* pointer, std::size_t size);
extern "C" void* malloc(std::size_t size) {
  heap_calls.fetch_add(1, std::memory_order_relaxed);
  return __libc_malloc(size);
}
extern "C" void* calloc(std::size_t count, std::size_t size) {
  heap_calls.fetch_add(1, std::memory_order_relaxed);
  return __libc_calloc(count, size);
}
extern "C" void* realloc(void* pointer, std::size_t size) {
  heap_calls.fetch_add(1, std::memory_order_relaxed);
  return __libc_realloc(pointer, size);
}
#endif

namespace bsg::envs {
namespace {

class StepAllocation : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
#ifndef BSG_COUNT_MALLOC
    GTEST_SKIP() << "malloc cannot be counted in this build";
#endif
  }
};

TEST_P(StepAllocation, StepAllocatesNothingAfterTheFirstEpisode) {
#ifdef BSG_COUNT_MALLOC
  const auto env = make(GetParam());
  const int action_dim = env->spec().action_dim;
  Rng rng(7);
  std::vector<double> action(static_cast<size_t>(action_dim));
  env->reset(3);
  // Warm-up: one whole episode of random play.
  for (bool done = false; !done;) {
    for (double& a : action) a = uniform(rng, -1, 1);
    const StepResult result = env->step(action);
    done = result.terminated || result.truncated;
  }
  // Counted: the steps of three more episodes with new layouts.
  long step_allocations = 0;
  int counted_steps = 0;
  for (int episode = 0; episode < 3; ++episode) {
    env->reset();
    for (bool done = false; !done; ++counted_steps) {
      for (double& a : action) a = uniform(rng, -1, 1);
      const long before = heap_calls.load();
      const StepResult result = env->step(action);
      step_allocations += heap_calls.load() - before;
      done = result.terminated || result.truncated;
    }
  }
  EXPECT_GT(counted_steps, 3);
  EXPECT_EQ(step_allocations, 0) << "heap allocations in " << counted_steps << " steps of "
                                 << GetParam();
#endif
}

INSTANTIATE_TEST_SUITE_P(AllEnvironments, StepAllocation,
                         ::testing::ValuesIn(registered_ids()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           std::string name = info.param;
                           for (char& c : name) {
                             if (c == '-') c = '_';
                           }
                           return name;
                         });

}  // namespace
}  // namespace bsg::envs
