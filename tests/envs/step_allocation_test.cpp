// Issue 3: "no allocation on the step path". Once an environment has been
// reset and has stepped through its first episode (Bullet sizes its pair
// cache, manifold pools and solver arrays then; later high-water marks of
// contact pairs are served by the block pool, envs/physics/bullet_block_pool.h),
// Env::step allocates nothing:
// heap allocations are counted by tests/heap_counter.h (Bullet's
// btAlignedAlloc and operator new included).
// Resets are not on the step path and are not counted.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "common/random.h"
#include "envs/env.h"

#include "tests/heap_counter.h"

namespace bsg::envs {
namespace {

class StepAllocation : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
    if (!testing::heap_calls_countable()) GTEST_SKIP() << "malloc cannot be counted in this build";
  }
};

TEST_P(StepAllocation, StepAllocatesNothingAfterTheFirstEpisode) {
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
      StepResult result;
      step_allocations += testing::allocations_of([&] { result = env->step(action); });
      done = result.terminated || result.truncated;
    }
  }
  EXPECT_GT(counted_steps, 3);
  EXPECT_EQ(step_allocations, 0) << "heap allocations in " << counted_steps << " steps of "
                                 << GetParam();
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
