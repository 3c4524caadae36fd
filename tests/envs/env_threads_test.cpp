// Environments on several threads at once (one Env per thread, as env.h
// asks) give bit for bit what the same seeds and actions give on one thread.
// Bullet's memory comes from per-thread block pools (envs/physics/bullet_block_pool.h)
// and Envs are built on one thread and stepped and destroyed on others, so
// blocks cross threads; nothing else is shared.
#include <gtest/gtest.h>

#include <cstdint>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "common/random.h"
#include "envs/env.h"

namespace bsg::envs {
namespace {

// Every observation, reward and cost of `episodes` episodes of random play.
std::vector<double> play(Env& env, std::uint64_t seed, int episodes) {
  Rng rng(seed);
  std::vector<double> trace;
  std::vector<double> action(static_cast<size_t>(env.spec().action_dim));
  env.reset(seed);
  for (int episode = 0; episode < episodes; ++episode) {
    if (episode > 0) env.reset();
    for (bool done = false; !done;) {
      for (double& a : action) a = uniform(rng, -1, 1);
      const StepResult result = env.step(action);
      trace.insert(trace.end(), result.observation.begin(), result.observation.end());
      trace.push_back(result.reward);
      trace.push_back(result.cost);
      done = result.terminated || result.truncated;
    }
  }
  return trace;
}

TEST(EnvThreads, ConcurrentEnvironmentsMatchTheirSingleThreadRuns) {
  const std::vector<std::string> ids = {"SafetyAntGather-v0", "SafetyCarReach-v0",
                                        "SafetyDroneReach-v0", "SafetyBallReach-v0"};
  std::vector<std::vector<double>> alone;
  for (size_t i = 0; i < ids.size(); ++i) {
    const auto env = make(ids[i]);
    alone.push_back(play(*env, 100 + i, 2));
  }
  // Built here, played and destroyed on their own threads.
  std::vector<std::unique_ptr<Env>> envs;
  for (const std::string& id : ids) envs.push_back(make(id));
  std::vector<std::vector<double>> together(ids.size());
  std::vector<std::thread> threads;
  for (size_t i = 0; i < ids.size(); ++i) {
    threads.emplace_back([&, i] {
      together[i] = play(*envs[i], 100 + i, 2);
      envs[i].reset();
    });
  }
  for (std::thread& thread : threads) thread.join();
  for (size_t i = 0; i < ids.size(); ++i) {
    ASSERT_EQ(together[i].size(), alone[i].size()) << ids[i];
    EXPECT_TRUE(together[i] == alone[i]) << ids[i] << " differs when run beside other threads";
  }
}

}  // namespace
}  // namespace bsg::envs
