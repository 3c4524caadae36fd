// The C++ side of tests/python/test_bit_identity.py: plays one environment
// with given actions straight through envs/env.h and writes every number it
// sees, so the Python module's rollouts can be compared bit for bit.
//   bsg_trajectory_recorder ENV_ID SEED RESET_EVERY ACTIONS_FILE OUTPUT_FILE
// ACTIONS_FILE holds float64 action rows (native byte order). The run resets
// with SEED, then for each row steps and, when the episode ended or
// RESET_EVERY steps passed since the last reset, resets again continuing the
// random stream. OUTPUT_FILE receives float64 values: the first observation,
// then per step the observation, reward, cost, terminated, truncated and the
// cost term values in the task's order, then after each reset its observation.
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <iterator>
#include <span>
#include <string>
#include <vector>

#include "envs/env.h"

int main(int argc, char** argv) {
  if (argc != 6) {
    std::cerr << "usage: bsg_trajectory_recorder ENV_ID SEED RESET_EVERY ACTIONS_FILE OUTPUT_FILE\n";
    return 2;
  }
  try {
    const auto env = bsg::envs::make(argv[1]);
    const std::uint64_t seed = std::stoull(argv[2]);
    const int reset_every = std::stoi(argv[3]);
    std::ifstream actions_file(argv[4], std::ios::binary);
    const std::vector<char> bytes((std::istreambuf_iterator<char>(actions_file)),
                                  std::istreambuf_iterator<char>());
    const auto act_dim = static_cast<size_t>(env->spec().action_dim);
    std::vector<double> actions(bytes.size() / sizeof(double));
    if (!actions_file || actions.size() % act_dim != 0 || actions.empty()) {
      std::cerr << "bsg_trajectory_recorder: " << argv[4] << " is not a whole number of "
                << act_dim << "-entry float64 rows\n";
      return 2;
    }
    std::copy(bytes.begin(), bytes.end(), reinterpret_cast<char*>(actions.data()));
    std::vector<double> record;
    auto append = [&record](std::span<const double> values) {
      record.insert(record.end(), values.begin(), values.end());
    };
    append(env->reset(seed));
    int since_reset = 0;
    for (size_t offset = 0; offset < actions.size(); offset += act_dim) {
      const bsg::envs::StepResult result =
          env->step(std::span<const double>(actions).subspan(offset, act_dim));
      append(result.observation);
      record.insert(record.end(), {result.reward, result.cost, double(result.terminated),
                                   double(result.truncated)});
      for (const bsg::envs::CostTerm& term : result.cost_terms) record.push_back(term.value);
      if (result.terminated || result.truncated || ++since_reset == reset_every) {
        append(env->reset());
        since_reset = 0;
      }
    }
    std::ofstream out(argv[5], std::ios::binary);
    out.write(reinterpret_cast<const char*>(record.data()),
              static_cast<std::streamsize>(record.size() * sizeof(double)));
    if (!out) {
      std::cerr << "bsg_trajectory_recorder: cannot write " << argv[5] << "\n";
      return 1;
    }
  } catch (const std::exception& error) {
    std::cerr << "bsg_trajectory_recorder: " << error.what() << "\n";
    return 1;
  }
  return 0;
}
