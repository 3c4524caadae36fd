// Steps SafetyAntRun-v0 for 100 steps through bsg's public environment header
// and prints what it saw, one "name value..." line each, every number with 17
// significant digits so that two builds can be compared exactly. Exits 1 if
// the environment breaks what the report's Table 3 says of it (33
// observations, 8 actions) or returns a non-finite number.
//
// Built twice: out of tree against an installed bsg (consumer/CMakeLists.txt)
// and in tree against the build's own library (tests/install/CMakeLists.txt).
#include <cmath>
#include <cstdio>
#include <span>
#include <vector>

#include "envs/env.h"

namespace {

constexpr int kSteps = 100;
constexpr int kObservationDim = 33;  // report Table 3: Ant, Run
constexpr int kActionDim = 8;

bool all_finite(std::span<const double> values) {
  for (double v : values) {
    if (!std::isfinite(v)) return false;
  }
  return true;
}

void print_values(const char* name, std::span<const double> values) {
  std::printf("%s", name);
  for (double v : values) std::printf(" %.17g", v);
  std::printf("\n");
}

}  // namespace

int main() {
  const auto env = bsg::envs::make("SafetyAntRun-v0");
  const bsg::envs::EnvSpec& spec = env->spec();
  if (spec.observation_dim != kObservationDim || spec.action_dim != kActionDim) {
    std::fprintf(stderr, "spec: %d observations, %d actions; expected %d and %d\n",
                 spec.observation_dim, spec.action_dim, kObservationDim, kActionDim);
    return 1;
  }
  const std::span<const double> first = env->reset(7);
  if (first.size() != static_cast<std::size_t>(kObservationDim) || !all_finite(first)) {
    std::fprintf(stderr, "reset: %zu observations or a non-finite one\n", first.size());
    return 1;
  }
  print_values("reset_observation", first);

  // A fixed, varied action sequence in [-1, 1]: every joint moves.
  std::vector<double> action(kActionDim);
  double reward_sum = 0, cost_sum = 0;
  int steps = 0;
  std::vector<double> last;
  for (; steps < kSteps; ++steps) {
    for (int i = 0; i < kActionDim; ++i) action[i] = std::sin(0.3 * steps + 0.7 * i);
    const bsg::envs::StepResult result = env->step(action);
    if (result.observation.size() != static_cast<std::size_t>(kObservationDim) ||
        !all_finite(result.observation) || !std::isfinite(result.reward)) {
      std::fprintf(stderr, "step %d: %zu observations or a non-finite number\n", steps,
                   result.observation.size());
      return 1;
    }
    reward_sum += result.reward;
    cost_sum += result.cost;
    last.assign(result.observation.begin(), result.observation.end());
    if (result.terminated || result.truncated) {
      ++steps;
      break;
    }
  }
  const bsg::envs::EnvState state = env->state();
  std::printf("steps %d\n", steps);
  print_values("last_observation", last);
  std::printf("reward_sum %.17g\ncost_sum %.17g\n", reward_sum, cost_sum);
  print_values("agent_position", state.agent_position);
  return 0;
}
