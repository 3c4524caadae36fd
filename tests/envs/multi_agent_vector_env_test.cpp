// MultiAgentVectorEnv (envs/multi_agent_vector_env.h) against its oracle,
// single MultiAgentEnvs played by hand: environment i reset with seed + i,
// stepped with its rows of the agents' actions and reset (continuing its
// stream) when the team's episode ends, gives bit for bit what the vector
// reports (observations, final observations, states, final states, rewards,
// costs, cost terms, flags) over several auto-resets, with 1 and 2 threads.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/random.h"
#include "envs/multi_agent_env.h"
#include "envs/multi_agent_vector_env.h"

namespace bsg::envs {
namespace {
// Its own names apart from the other files of its test batch (tests/CMakeLists.txt).
namespace multi_agent_vector_env_test {

// Everything reported over an episode of steps, flattened in one order.
struct Trace {
  std::vector<double> observations, final_observations, states, final_states;
  std::vector<double> rewards, costs, cost_terms;
  std::vector<int> terminated, truncated;
};

void append(std::vector<double>& out, std::span<const double> in) {
  out.insert(out.end(), in.begin(), in.end());
}

// One N x action_dims[agent] array per agent, uniform in [-1, 1], drawn from (seed, step).
std::vector<std::vector<double>> random_actions(const MultiAgentSpec& spec, int num_envs,
                                                std::uint64_t step) {
  Rng rng(1000 + step);
  std::vector<std::vector<double>> actions;
  for (const int dim : spec.action_dims) {
    std::vector<double>& array = actions.emplace_back(static_cast<size_t>(num_envs * dim));
    for (double& a : array) a = uniform(rng, -1, 1);
  }
  return actions;
}

std::vector<std::span<const double>> spans(const std::vector<std::vector<double>>& arrays) {
  return {arrays.begin(), arrays.end()};
}

Trace play_vector(const MultiAgentDescription& description, int num_envs, int num_threads,
                  int steps, std::uint64_t seed) {
  MultiAgentVectorEnv vector(description, num_envs, num_threads);
  vector.reset(seed);
  Trace trace;
  const int agents = vector.agent_count();
  for (int agent = 0; agent < agents; ++agent) append(trace.observations, vector.observations(agent));
  append(trace.states, vector.states());
  for (int t = 0; t < steps; ++t) {
    const auto actions = random_actions(vector.spec(), num_envs, static_cast<std::uint64_t>(t));
    vector.step(spans(actions));
    for (int agent = 0; agent < agents; ++agent) {
      append(trace.observations, vector.observations(agent));
      append(trace.final_observations, vector.final_observations(agent));
    }
    append(trace.states, vector.states());
    append(trace.final_states, vector.final_states());
    append(trace.rewards, vector.rewards());
    append(trace.costs, vector.costs());
    append(trace.cost_terms, vector.cost_terms());
    trace.terminated.insert(trace.terminated.end(), vector.terminated().begin(), vector.terminated().end());
    trace.truncated.insert(trace.truncated.end(), vector.truncated().begin(), vector.truncated().end());
  }
  return trace;
}

// The oracle: one MultiAgentEnv per index, written into the vector's layout by hand.
Trace play_by_hand(const MultiAgentDescription& description, int num_envs, int steps,
                   std::uint64_t seed) {
  std::vector<std::unique_ptr<MultiAgentEnv>> envs;
  for (int i = 0; i < num_envs; ++i) envs.push_back(make_multi_agent(description));
  const MultiAgentSpec& spec = envs[0]->spec();
  const int agents = spec.agent_count();
  // observations[agent][env], states[env]: what each environment shows now.
  std::vector<std::vector<std::vector<double>>> observations(static_cast<size_t>(agents));
  std::vector<std::vector<double>> states;
  auto keep = [&](int i, std::span<const std::span<const double>> shown) {
    for (int agent = 0; agent < agents; ++agent) {
      const std::span<const double> o = shown[static_cast<size_t>(agent)];
      observations[static_cast<size_t>(agent)][static_cast<size_t>(i)].assign(o.begin(), o.end());
    }
    const std::span<const double> s = envs[static_cast<size_t>(i)]->global_state();
    states[static_cast<size_t>(i)].assign(s.begin(), s.end());
  };
  for (auto& per_env : observations) per_env.resize(static_cast<size_t>(num_envs));
  states.resize(static_cast<size_t>(num_envs));
  for (int i = 0; i < num_envs; ++i) keep(i, envs[static_cast<size_t>(i)]->reset(seed + static_cast<std::uint64_t>(i)));
  Trace trace;
  auto record_shown = [&] {
    for (const auto& per_env : observations) {
      for (const auto& o : per_env) append(trace.observations, o);
    }
    for (const auto& s : states) append(trace.states, s);
  };
  record_shown();
  for (int t = 0; t < steps; ++t) {
    const auto actions = random_actions(spec, num_envs, static_cast<std::uint64_t>(t));
    std::vector<std::vector<std::vector<double>>> finals(static_cast<size_t>(agents));
    std::vector<double> final_states;
    for (int i = 0; i < num_envs; ++i) {
      MultiAgentEnv& env = *envs[static_cast<size_t>(i)];
      std::vector<std::span<const double>> rows;
      for (int agent = 0; agent < agents; ++agent) {
        const int dim = spec.action_dims[static_cast<size_t>(agent)];
        rows.push_back(std::span<const double>(actions[static_cast<size_t>(agent)]).subspan(
            static_cast<size_t>(i * dim), static_cast<size_t>(dim)));
      }
      const MultiAgentStepResult r = env.step(rows);
      for (int agent = 0; agent < agents; ++agent) {
        const auto a = static_cast<size_t>(agent);
        finals[a].emplace_back(r.observations[a].begin(), r.observations[a].end());
        trace.rewards.push_back(r.rewards[a]);
        trace.costs.push_back(r.costs[a]);
        for (const CostTerm& term : r.cost_terms[a]) trace.cost_terms.push_back(term.value);
      }
      append(final_states, env.global_state());
      trace.terminated.push_back(r.terminated);
      trace.truncated.push_back(r.truncated);
      keep(i, r.terminated || r.truncated ? env.reset() : r.observations);
    }
    for (const auto& per_env : observations) {
      for (const auto& o : per_env) append(trace.observations, o);
    }
    for (const auto& per_env : finals) {
      for (const auto& o : per_env) append(trace.final_observations, o);
    }
    for (const auto& s : states) append(trace.states, s);
    append(trace.final_states, final_states);
  }
  return trace;
}

void expect_identical(const Trace& a, const Trace& b, const std::string& what) {
  EXPECT_TRUE(a.observations == b.observations) << what << ": observations differ";
  EXPECT_TRUE(a.final_observations == b.final_observations) << what << ": final observations differ";
  EXPECT_TRUE(a.states == b.states) << what << ": states differ";
  EXPECT_TRUE(a.final_states == b.final_states) << what << ": final states differ";
  EXPECT_TRUE(a.rewards == b.rewards) << what << ": rewards differ";
  EXPECT_TRUE(a.costs == b.costs) << what << ": costs differ";
  EXPECT_TRUE(a.cost_terms == b.cost_terms) << what << ": cost terms differ";
  EXPECT_EQ(a.terminated, b.terminated) << what;
  EXPECT_EQ(a.truncated, b.truncated) << what;
}

int episode_ends(const Trace& trace) {
  int ends = 0;
  for (size_t k = 0; k < trace.terminated.size(); ++k) ends += trace.terminated[k] || trace.truncated[k];
  return ends;
}

// Episodes of 7 steps: 20 steps cross two auto-resets of each of 3 environments.
TEST(MultiAgentVectorEnv, EnvironmentIPlaysWhatAMultiAgentEnvSeededWithSeedPlusIPlays) {
  const MultiAgentDescription description =
      describe_multi_agent("SafetyBallCircle2-v0", {{"max_episode_steps", "7"}});
  const Trace oracle = play_by_hand(description, 3, 20, 7);
  ASSERT_EQ(episode_ends(oracle), 6) << "the test must cross auto-resets";
  expect_identical(play_vector(description, 3, 1, 20, 7), oracle, "1 thread");
  expect_identical(play_vector(description, 3, 2, 20, 7), oracle, "2 threads");
}

// Four agents of one Ant, the team's reward and cost; the Ant may also terminate.
TEST(MultiAgentVectorEnv, TheSplitAntMatchesItsOracleToo) {
  const MultiAgentDescription description =
      describe_multi_agent("SafetyAntCircle4x2-v0", {{"max_episode_steps", "4"}});
  const Trace oracle = play_by_hand(description, 2, 9, 3);
  ASSERT_GE(episode_ends(oracle), 4);
  expect_identical(play_vector(description, 2, 2, 9, 3), oracle, "2 threads");
}

TEST(MultiAgentVectorEnv, BuffersHaveOneArrayPerAgentAndOneRowPerEnvironment) {
  MultiAgentVectorEnv vector("SafetyBallCircle3-v0", 4, 2);
  const MultiAgentSpec& spec = vector.spec();
  vector.reset(0);
  ASSERT_EQ(vector.agent_count(), 3);
  for (int agent = 0; agent < 3; ++agent) {
    // docs/multi_agent.md#ids: 12 entries per agent, 2 actions, a state of 24.
    EXPECT_EQ(vector.observations(agent).size(), 4u * 12u);
    EXPECT_EQ(vector.final_observations(agent).size(), 4u * 12u);
  }
  EXPECT_EQ(vector.states().size(), 4u * 24u);
  EXPECT_EQ(vector.rewards().size(), 4u * 3u);
  EXPECT_EQ(vector.cost_terms().size(), 4u * 3u * spec.cost_term_names.size());
  EXPECT_EQ(vector.terminated().size(), 4u);
  EXPECT_THROW(vector.observations(3), std::out_of_range);
}

// restart(seed) after play gives a new vector's episode; a plain reset(seed)
// need not (a reset is not a pure function of its seed, envs/env.h), so the
// oracle is a new vector.
TEST(MultiAgentVectorEnv, RestartIsAFreshStart) {
  const std::string id = "SafetyCarCircle2-v0";
  MultiAgentVectorEnv fresh(id, 2, 1);
  fresh.reset(5);
  MultiAgentVectorEnv played(id, 2, 2);
  played.reset(1);
  const std::vector<std::vector<double>> full(2, std::vector<double>(4, 0.9));
  for (int t = 0; t < 30; ++t) played.step(spans(full));
  played.restart(5);
  for (int agent = 0; agent < 2; ++agent) {
    EXPECT_TRUE(std::ranges::equal(played.observations(agent), fresh.observations(agent)));
  }
  EXPECT_TRUE(std::ranges::equal(played.states(), fresh.states()));
  played.step(spans(full));
  fresh.step(spans(full));
  EXPECT_TRUE(std::ranges::equal(played.states(), fresh.states()));
}

std::string message_of(const std::function<void()>& call) {
  try {
    call();
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  return "(nothing thrown)";
}

void expect_one_line_naming(const std::string& message, const std::string& problem) {
  EXPECT_NE(message.find(problem), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

TEST(MultiAgentVectorEnv, BadInputIsRefusedInOneLineWithoutSteppingAnything) {
  const std::string id = "SafetyBallCircle2-v0";
  expect_one_line_naming(message_of([&] { MultiAgentVectorEnv(id, 0); }), "num_envs must be >= 1, got 0");
  expect_one_line_naming(message_of([&] { MultiAgentVectorEnv(id, 2, -1); }), "num_threads must be >= 0");
  expect_one_line_naming(message_of([] { MultiAgentVectorEnv("SafetyBallCircle-v0", 2); }),
                         "SafetyBallCircle2-v0");  // a single-agent id: the multi-agent ids are listed
  MultiAgentVectorEnv vector(id, 2, 2);
  const std::vector<std::vector<double>> zeros(2, std::vector<double>(4, 0.0));
  EXPECT_THROW(vector.step(spans(zeros)), std::logic_error);
  vector.reset(5);
  const std::vector<double> before(vector.observations(1).begin(), vector.observations(1).end());
  const std::vector<std::vector<double>> one_array(1, std::vector<double>(4, 0.0));
  expect_one_line_naming(message_of([&] { vector.step(spans(one_array)); }),
                         "got 1 action arrays, expected one per agent (2)");
  std::vector<std::vector<double>> short_rows = zeros;
  short_rows[1].resize(3);
  expect_one_line_naming(message_of([&] { vector.step(spans(short_rows)); }),
                         "agent_1's actions have 3 entries, expected 2 x 2");
  std::vector<std::vector<double>> not_finite = zeros;
  not_finite[1][3] = std::nan("");  // environment 1, agent_1's entry 1
  expect_one_line_naming(message_of([&] { vector.step(spans(not_finite)); }),
                         "environment 1: agent_1's action entry 1 is not finite");
  EXPECT_TRUE(std::ranges::equal(vector.observations(1), before));
  // Nothing was stepped: the next step is the first step of a new vector reset with 5.
  MultiAgentVectorEnv oracle(id, 2, 1);
  oracle.reset(5);
  vector.step(spans(zeros));
  oracle.step(spans(zeros));
  EXPECT_TRUE(std::ranges::equal(vector.states(), oracle.states()));
}

}  // namespace multi_agent_vector_env_test
}  // namespace
}  // namespace bsg::envs
