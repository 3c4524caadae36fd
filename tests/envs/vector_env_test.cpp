// VectorEnv against its oracle, single Envs played by hand: environment i
// reset with seed + i, stepped with its row of actions and reset (continuing
// its stream) when its episode ends, gives bit for bit what VectorEnv reports,
// whatever the number of threads.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/random.h"
#include "envs/env.h"
#include "envs/vector_env.h"

namespace bsg::envs {
namespace {

// Everything a VectorEnv reports over `steps` steps, flattened.
struct Trace {
  std::vector<double> observations, final_observations, rewards, costs, cost_terms;
  std::vector<int> terminated, truncated;
};

std::vector<double> random_actions(int count, std::uint64_t seed) {
  Rng rng(seed);
  std::vector<double> actions(static_cast<size_t>(count));
  for (double& a : actions) a = uniform(rng, -1, 1);
  return actions;
}

Trace play_vector(const std::string& id, int num_envs, int num_threads, int steps,
                  std::uint64_t seed) {
  VectorEnv vector(id, num_envs, num_threads);
  vector.reset(seed);
  Trace trace;
  trace.observations.assign(vector.observations().begin(), vector.observations().end());
  const int act_dim = vector.spec().action_dim;
  for (int t = 0; t < steps; ++t) {
    vector.step(random_actions(num_envs * act_dim, 1000 + t));
    auto append = [](std::vector<double>& out, std::span<const double> in) {
      out.insert(out.end(), in.begin(), in.end());
    };
    append(trace.observations, vector.observations());
    append(trace.final_observations, vector.final_observations());
    append(trace.rewards, vector.rewards());
    append(trace.costs, vector.costs());
    append(trace.cost_terms, vector.cost_terms());
    trace.terminated.insert(trace.terminated.end(), vector.terminated().begin(),
                            vector.terminated().end());
    trace.truncated.insert(trace.truncated.end(), vector.truncated().begin(),
                           vector.truncated().end());
  }
  return trace;
}

// The oracle: one Env per index, played in the same order by hand.
Trace play_by_hand(const std::string& id, int num_envs, int steps, std::uint64_t seed) {
  std::vector<std::unique_ptr<Env>> envs;
  for (int i = 0; i < num_envs; ++i) envs.push_back(make(id));
  const int obs_dim = envs[0]->spec().observation_dim;
  const int act_dim = envs[0]->spec().action_dim;
  std::vector<double> observations(static_cast<size_t>(num_envs * obs_dim));
  for (int i = 0; i < num_envs; ++i) {
    const auto first = envs[i]->reset(seed + static_cast<std::uint64_t>(i));
    std::copy(first.begin(), first.end(), observations.begin() + i * obs_dim);
  }
  Trace trace;
  trace.observations = observations;
  for (int t = 0; t < steps; ++t) {
    const std::vector<double> actions = random_actions(num_envs * act_dim, 1000 + t);
    for (int i = 0; i < num_envs; ++i) {
      const StepResult r =
          envs[i]->step(std::span<const double>(actions).subspan(i * act_dim, act_dim));
      trace.final_observations.insert(trace.final_observations.end(), r.observation.begin(),
                                      r.observation.end());
      trace.rewards.push_back(r.reward);
      trace.costs.push_back(r.cost);
      for (const CostTerm& term : r.cost_terms) trace.cost_terms.push_back(term.value);
      trace.terminated.push_back(r.terminated);
      trace.truncated.push_back(r.truncated);
      const auto next = r.terminated || r.truncated ? envs[i]->reset() : r.observation;
      std::copy(next.begin(), next.end(), observations.begin() + i * obs_dim);
    }
    trace.observations.insert(trace.observations.end(), observations.begin(),
                              observations.end());
  }
  return trace;
}

void expect_identical(const Trace& a, const Trace& b, const std::string& what) {
  EXPECT_TRUE(a.observations == b.observations) << what << ": observations differ";
  EXPECT_TRUE(a.final_observations == b.final_observations) << what << ": final observations";
  EXPECT_TRUE(a.rewards == b.rewards) << what << ": rewards differ";
  EXPECT_TRUE(a.costs == b.costs) << what << ": costs differ";
  EXPECT_TRUE(a.cost_terms == b.cost_terms) << what << ": cost terms differ";
  EXPECT_EQ(a.terminated, b.terminated) << what;
  EXPECT_EQ(a.truncated, b.truncated) << what;
}

// BallRun's episodes end early (the ball leaves the corridor) or at 250 steps:
// 600 steps cross several auto-resets of every environment.
TEST(VectorEnv, EnvironmentIPlaysWhatASingleEnvSeededWithSeedPlusIPlays) {
  const std::string id = "SafetyBallRun-v0";
  const Trace oracle = play_by_hand(id, 3, 600, 7);
  int episode_ends = 0;
  for (size_t k = 0; k < oracle.terminated.size(); ++k) {
    episode_ends += oracle.terminated[k] || oracle.truncated[k];
  }
  ASSERT_GE(episode_ends, 6) << "the test must cross auto-resets";
  expect_identical(play_vector(id, 3, 1, 600, 7), oracle, "1 thread");
  expect_identical(play_vector(id, 3, 2, 600, 7), oracle, "2 threads");
}

TEST(VectorEnv, ResultsDoNotDependOnTheNumberOfThreads) {
  const std::string id = "SafetyCarGather-v0";
  const Trace one = play_vector(id, 5, 1, 120, 3);
  expect_identical(play_vector(id, 5, 2, 120, 3), one, "2 threads");
  expect_identical(play_vector(id, 5, 3, 120, 3), one, "3 threads");
}

TEST(VectorEnv, CostTermsAreNamedAfterTheFirstStep) {
  VectorEnv vector("SafetyBallCircle-v0", 2, 2);
  EXPECT_TRUE(vector.cost_term_names().empty());
  vector.reset(0);
  vector.step(std::vector<double>(4, 0.0));
  const auto single = make("SafetyBallCircle-v0");
  single->reset(0);
  const StepResult r = single->step(std::vector<double>(2, 0.0));
  ASSERT_EQ(vector.cost_term_names().size(), r.cost_terms.size());
  for (size_t k = 0; k < r.cost_terms.size(); ++k) {
    EXPECT_EQ(vector.cost_term_names()[k], r.cost_terms[k].name);
  }
  EXPECT_EQ(vector.cost_terms().size(), 2 * r.cost_terms.size());
}

TEST(VectorEnv, BadInputIsRejectedWithoutSteppingAnything) {
  EXPECT_THROW(VectorEnv("SafetyBallCircle-v0", 0), std::invalid_argument);
  EXPECT_THROW(VectorEnv("SafetyBallCircle-v0", 2, -1), std::invalid_argument);
  EXPECT_THROW(VectorEnv("NoSuchEnv-v0", 2), std::invalid_argument);
  VectorEnv vector("SafetyBallCircle-v0", 2, 2);
  EXPECT_EQ(vector.num_threads(), 2);
  EXPECT_THROW(vector.step(std::vector<double>(4, 0.0)), std::logic_error);
  vector.reset(5);
  const std::vector<double> before(vector.observations().begin(), vector.observations().end());
  EXPECT_THROW(vector.step(std::vector<double>(3, 0.0)), std::invalid_argument);
  std::vector<double> actions(4, 0.0);
  actions[3] = std::nan("");
  try {
    vector.step(actions);
    ADD_FAILURE() << "a NaN action was accepted";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("[1, 1]"), std::string::npos) << error.what();
  }
  EXPECT_TRUE(std::vector<double>(vector.observations().begin(), vector.observations().end()) ==
              before);
}

TEST(VectorEnv, NumThreadsZeroMeansHardwareThreadsAtMostNumEnvs) {
  VectorEnv one_env("SafetyBallCircle-v0", 1, 0);
  EXPECT_EQ(one_env.num_threads(), 1);
  VectorEnv many("SafetyBallCircle-v0", 8, 0);
  EXPECT_GE(many.num_threads(), 1);
  EXPECT_LE(many.num_threads(), 8);
}

std::vector<double> row(std::span<const double> values, int index, int width) {
  const auto begin = values.begin() + static_cast<std::ptrdiff_t>(index) * width;
  return {begin, begin + width};
}

std::vector<double> fresh_reset(const std::string& id, std::uint64_t seed) {
  const auto env = make(id);
  const std::span<const double> observation = env->reset(seed);
  return {observation.begin(), observation.end()};
}

// Oracle: a new Env reset with the seed. The Car keeps motor targets and the
// Reach task its first-reset draws across a plain reset(seed); a seeded
// reset_selected() must not.
TEST(VectorEnv, ResetSelectedWithASeedIsAFreshStartAndLeavesOthersAlone) {
  const std::string id = "SafetyCarReach-v0";
  VectorEnv vector(id, 3, 2);
  vector.reset(4);
  for (int t = 0; t < 40; ++t) vector.step(std::vector<double>(6, 0.8));
  const int obs_dim = vector.spec().observation_dim;
  const std::vector<double> untouched = row(vector.observations(), 1, obs_dim);
  const std::vector<std::uint8_t> mask{1, 0, 1};
  const std::vector<std::optional<std::uint64_t>> seeds{11, std::nullopt, std::nullopt};
  vector.reset_selected(mask, seeds);
  EXPECT_EQ(row(vector.observations(), 0, obs_dim), fresh_reset(id, 11));
  EXPECT_EQ(row(vector.observations(), 1, obs_dim), untouched);
  // Environment 2 continued its stream: a single env with the same history.
  const auto single = make(id);
  single->reset(6);
  for (int t = 0; t < 40; ++t) single->step(std::vector<double>(2, 0.8));
  const std::span<const double> continued = single->reset();
  EXPECT_EQ(row(vector.observations(), 2, obs_dim),
            std::vector<double>(continued.begin(), continued.end()));
  EXPECT_THROW(vector.reset_selected(std::vector<std::uint8_t>(2, 1), {}), std::invalid_argument);
}

// Oracle: a single Env truncated after 4 steps by hand; the step after the end
// resets it (reward 0, flags false) instead of stepping it.
TEST(VectorEnv, NextStepAutoResetAndEpisodeLengthOverride) {
  const std::string id = "SafetyBallCircle-v0";
  VectorEnv vector(id, 2, 2);
  vector.set_autoreset(AutoReset::kNextStep);
  vector.set_max_episode_steps(4);
  EXPECT_EQ(vector.max_episode_steps(), 4);
  EXPECT_THROW(vector.set_max_episode_steps(-1), std::invalid_argument);
  vector.reset(3);
  const auto single = make(id);
  single->reset(3);
  const int obs_dim = vector.spec().observation_dim;
  for (int t = 1; t <= 4; ++t) {
    vector.step(std::vector<double>(4, 0.5));
    const StepResult r = single->step(std::vector<double>(2, 0.5));
    EXPECT_EQ(row(vector.observations(), 0, obs_dim),
              std::vector<double>(r.observation.begin(), r.observation.end()));
    EXPECT_EQ(vector.rewards()[0], r.reward);
    EXPECT_EQ(vector.truncated()[0], t == 4) << "step " << t;
    EXPECT_EQ(vector.autoreset_envs()[0], 0);
  }
  vector.step(std::vector<double>(4, 0.5));
  const std::span<const double> next = single->reset();
  EXPECT_EQ(row(vector.observations(), 0, obs_dim), std::vector<double>(next.begin(), next.end()));
  EXPECT_EQ(vector.rewards()[0], 0.0);
  EXPECT_EQ(vector.truncated()[0], 0);
  EXPECT_EQ(vector.autoreset_envs()[0], 1);
  vector.step(std::vector<double>(4, 0.5));
  EXPECT_EQ(vector.autoreset_envs()[0], 0);
}

}  // namespace
}  // namespace bsg::envs
