#include "envs/env_benchmark.h"

#include <chrono>
#include <stdexcept>
#include <vector>

#include "common/random.h"
#include "envs/assembly/assembled_env.h"
#include "envs/assembly/env_builder.h"
#include "envs/assembly/registry.h"

namespace bsg::envs {
namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

EnvBenchmark benchmark_env(const std::string& id, long steps, std::uint64_t seed,
                           const EnvOptions& options) {
  return benchmark_env(find_description(id), steps, seed, options);
}

EnvBenchmark benchmark_env(const EnvDescription& description, long steps, std::uint64_t seed,
                           const EnvOptions& options) {
  if (steps < 1) throw std::invalid_argument("benchmark_env: steps must be >= 1");
  EnvBenchmark result;
  result.id = description.name;
  result.steps = steps;
  Rng rng(seed);

  {
    const std::unique_ptr<Env> env = build_env(description, options);
    std::vector<double> action(static_cast<size_t>(env->spec().action_dim));
    env->reset(seed);
    const auto start = std::chrono::steady_clock::now();
    for (long i = 0; i < steps; ++i) {
      for (double& a : action) a = uniform(rng, -1, 1);
      const StepResult step = env->step(action);
      if (step.terminated || step.truncated) env->reset();
    }
    result.env_steps_per_second = static_cast<double>(steps) / seconds_since(start);
  }
  {
    // The same scene, driven by the same kind of actions, without the task.
    const std::unique_ptr<Env> env = build_env(description, options);
    auto& assembled = static_cast<AssembledEnv&>(*env);
    std::vector<double> action(static_cast<size_t>(env->spec().action_dim));
    env->reset(seed);
    const int episode = env->spec().max_episode_steps;
    const auto start = std::chrono::steady_clock::now();
    for (long i = 0; i < steps; ++i) {
      for (double& a : action) a = uniform(rng, -1, 1);
      assembled.agent().apply_action(action);
      assembled.world().step();
      // Keep the agent in the scene as the environment does (an episode's worth at most).
      if ((i + 1) % episode == 0) env->reset();
    }
    result.physics_steps_per_second = static_cast<double>(steps) / seconds_since(start);
  }
  return result;
}

}  // namespace bsg::envs
