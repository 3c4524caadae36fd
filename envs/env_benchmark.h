// Speed of an environment on one core, beside the raw physics rate of the same
// scene (agent actions and engine steps only: no task, sensor or observation
// work), so that the framework's overhead is visible (`bsg bench`,
// tests/bench/env_bench.cpp, the Python module's _benchmark_env). Part of the
// face: the programs above envs/ reach the raw physics rate through it alone.
#pragma once

#include <cstdint>
#include <string>

#include "envs/env.h"

namespace bsg::envs {

struct EnvBenchmark {
  std::string id;
  long steps = 0;
  double env_steps_per_second = 0;      // step() with random actions, resets included
  double physics_steps_per_second = 0;  // apply_action + World::step() only
};

// Runs `steps` environment steps with uniform random actions in [−1, 1], then
// the same number of raw physics steps, both built with `options`; throws
// std::invalid_argument for an unknown id, steps < 1 or options make() rejects.
EnvBenchmark benchmark_env(const std::string& id, long steps, std::uint64_t seed = 0,
                           const EnvOptions& options = {});
// The same for any description (custom ones included).
EnvBenchmark benchmark_env(const EnvDescription& description, long steps, std::uint64_t seed = 0,
                           const EnvOptions& options = {});

}  // namespace bsg::envs
