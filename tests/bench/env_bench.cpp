// Environment speed on one core: env steps per second with random actions for
// every registered environment (or those named on the command line), beside
// the raw physics rate of the same world. Printed, never asserted.
//   bsg_env_bench [STEPS] [ID...]
#include <algorithm>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <string>
#include <vector>

#include "envs/env.h"
#include "envs/env_benchmark.h"

int main(int argc, char** argv) {
  const long steps = argc > 1 ? std::atol(argv[1]) : 20000;
  std::vector<std::string> ids(argv + std::min(argc, 2), argv + argc);
  if (ids.empty()) ids = bsg::envs::registered_ids();
  std::cout << std::left << std::setw(24) << "id" << std::right << std::setw(14) << "env steps/s"
            << std::setw(18) << "physics steps/s" << std::setw(12) << "overhead" << "\n";
  for (const std::string& id : ids) {
    const bsg::envs::EnvBenchmark r = bsg::envs::benchmark_env(id, steps);
    std::cout << std::left << std::setw(24) << id << std::right << std::fixed
              << std::setprecision(0) << std::setw(14) << r.env_steps_per_second << std::setw(18)
              << r.physics_steps_per_second << std::setprecision(2) << std::setw(11)
              << r.physics_steps_per_second / r.env_steps_per_second << "x" << std::endl;
  }
  return 0;
}
