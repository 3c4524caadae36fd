// Multi-agent environment speed on one core, as ratios taken in one run: team steps per second
// of each multi-agent id with uniform random actions, beside the single-agent id of the same
// robot and task, the two timed in alternating rounds so that the machine's load falls on both.
// Also the agent-steps rate (team steps times agents). Printed, never asserted.
//   bsg_multi_agent_env_bench [STEPS_PER_ROUND] [ROUNDS]
#include <chrono>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <span>
#include <string>
#include <vector>

#include "common/random.h"
#include "envs/env.h"
#include "envs/multi_agent_env.h"

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Seconds for `steps` single-agent steps with random actions, resetting at each episode's end.
double time_single(bsg::envs::Env& env, long steps, bsg::Rng& rng) {
  std::vector<double> action(static_cast<std::size_t>(env.spec().action_dim));
  env.reset();
  const Clock::time_point start = Clock::now();
  for (long i = 0; i < steps; ++i) {
    for (double& a : action) a = bsg::uniform(rng, -1, 1);
    const bsg::envs::StepResult r = env.step(action);
    if (r.terminated || r.truncated) env.reset();
  }
  return seconds_since(start);
}

// Seconds for `steps` team steps with random actions for every agent.
double time_team(bsg::envs::MultiAgentEnv& env, long steps, bsg::Rng& rng) {
  const bsg::envs::MultiAgentSpec& spec = env.spec();
  std::vector<std::vector<double>> actions;
  for (const int dim : spec.action_dims) actions.emplace_back(static_cast<std::size_t>(dim));
  const std::vector<std::span<const double>> views(actions.begin(), actions.end());
  env.reset();
  const Clock::time_point start = Clock::now();
  for (long i = 0; i < steps; ++i) {
    for (std::vector<double>& action : actions) {
      for (double& a : action) a = bsg::uniform(rng, -1, 1);
    }
    const bsg::envs::MultiAgentStepResult r = env.step(views);
    if (r.terminated || r.truncated) env.reset();
  }
  return seconds_since(start);
}

}  // namespace

int main(int argc, char** argv) {
  const long steps = argc > 1 ? std::atol(argv[1]) : 5000;
  const int rounds = argc > 2 ? std::atoi(argv[2]) : 4;
  if (steps < 1 || rounds < 1) {
    std::cerr << "bsg_multi_agent_env_bench: STEPS_PER_ROUND and ROUNDS must be positive\n";
    return 2;
  }
  const std::vector<std::pair<std::string, std::string>> pairs = {
      {"SafetyBallCircle2-v0", "SafetyBallCircle-v0"}, {"SafetyBallCircle3-v0", "SafetyBallCircle-v0"},
      {"SafetyCarCircle2-v0", "SafetyCarCircle-v0"},   {"SafetyBallReach2-v0", "SafetyBallReach-v0"},
      {"SafetyAntRun2x4-v0", "SafetyAntRun-v0"},       {"SafetyAntRun4x2-v0", "SafetyAntRun-v0"}};
  std::cout << std::left << std::setw(24) << "multi-agent id" << std::setw(22) << "single-agent id" << std::right
            << std::setw(14) << "team steps/s" << std::setw(15) << "agent steps/s" << std::setw(16)
            << "single steps/s" << std::setw(18) << "team / single" << "\n";
  for (const auto& [multi_id, single_id] : pairs) {
    const std::unique_ptr<bsg::envs::MultiAgentEnv> team = bsg::envs::make_multi_agent(multi_id);
    const std::unique_ptr<bsg::envs::Env> single = bsg::envs::make(single_id);
    team->reset(0);
    single->reset(0);
    bsg::Rng rng(1);
    double team_seconds = 0, single_seconds = 0;
    for (int round = 0; round < rounds; ++round) {
      team_seconds += time_team(*team, steps, rng);
      single_seconds += time_single(*single, steps, rng);
    }
    const double total = static_cast<double>(steps) * rounds;
    const double team_rate = total / team_seconds, single_rate = total / single_seconds;
    std::cout << std::left << std::setw(24) << multi_id << std::setw(22) << single_id << std::right << std::fixed
              << std::setprecision(0) << std::setw(14) << team_rate << std::setw(15)
              << team_rate * team->spec().agent_count() << std::setw(16) << single_rate << std::setprecision(2)
              << std::setw(18) << team_rate / single_rate << std::endl;
  }
  return 0;
}
