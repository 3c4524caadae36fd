// One conformance suite run over every registered environment (OpenSpiel's
// shared suite): dimensions and limits of docs/environments.md#the-sixteen-environments, invariants at every step
// of random play (finite values, cost in {0, 1}, |obs| < 5 as in the
// original's own test suite, docs/environments.md#test-oracles), truncation exactly at the
// episode length, determinism across instances, and rejection of bad actions.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "common/random.h"
#include "envs/env.h"

namespace bsg::envs {
namespace {

struct ExpectedSpec {
  int observation_dim;
  int action_dim;
  int max_episode_steps;
  double cost_limit;
};

// docs/environments.md#the-sixteen-environments: the registration table (obs/act dims, episode length) and the
// report's Table 3 (cost limit d).
const std::map<std::string, ExpectedSpec>& expected_specs() {
  static const std::map<std::string, ExpectedSpec> table = {
      {"SafetyBallCircle-v0", {8, 2, 250, 25}},     {"SafetyBallGather-v0", {39, 2, 250, 0.2}},
      {"SafetyBallReach-v0", {57, 2, 250, 10}},     {"SafetyBallRun-v0", {7, 2, 250, 25}},
      {"SafetyCarCircle-v0", {8, 2, 500, 25}},      {"SafetyCarGather-v0", {39, 2, 500, 0.2}},
      {"SafetyCarReach-v0", {57, 2, 500, 10}},      {"SafetyCarRun-v0", {7, 2, 500, 25}},
      {"SafetyDroneCircle-v0", {18, 4, 500, 25}},   {"SafetyDroneGather-v0", {49, 4, 500, 0.2}},
      {"SafetyDroneReach-v0", {67, 4, 500, 10}},    {"SafetyDroneRun-v0", {17, 4, 500, 25}},
      {"SafetyAntCircle-v0", {34, 8, 1000, 25}},    {"SafetyAntGather-v0", {65, 8, 1000, 0.2}},
      {"SafetyAntReach-v0", {83, 8, 1000, 25}},     {"SafetyAntRun-v0", {33, 8, 1000, 25}},
      // The fork variant (docs/environments.md#the-fork-variant): shorter Circle and Run
      // episodes; CarReach without Box and LIDAR (7 + 24 + 2).
      {"SafetyBallCircle-fork", {8, 2, 200, 25}},   {"SafetyBallGather-fork", {39, 2, 250, 0.2}},
      {"SafetyBallReach-fork", {57, 2, 250, 10}},   {"SafetyBallRun-fork", {7, 2, 100, 25}},
      {"SafetyCarCircle-fork", {8, 2, 300, 25}},    {"SafetyCarGather-fork", {39, 2, 500, 0.2}},
      {"SafetyCarReach-fork", {33, 2, 500, 10}},    {"SafetyCarRun-fork", {7, 2, 200, 25}},
      {"SafetyDroneCircle-fork", {18, 4, 300, 25}}, {"SafetyDroneGather-fork", {49, 4, 500, 0.2}},
      {"SafetyDroneReach-fork", {67, 4, 500, 10}},  {"SafetyDroneRun-fork", {17, 4, 200, 25}},
      {"SafetyAntCircle-fork", {34, 8, 500, 25}},   {"SafetyAntGather-fork", {65, 8, 1000, 0.2}},
      {"SafetyAntReach-fork", {83, 8, 1000, 25}},   {"SafetyAntRun-fork", {33, 8, 200, 25}},
  };
  return table;
}

std::vector<double> random_action(Rng& rng, int dim) {
  std::vector<double> action(static_cast<size_t>(dim));
  for (double& a : action) a = uniform(rng, -1, 1);
  return action;
}

class Conformance : public ::testing::TestWithParam<std::string> {};

TEST_P(Conformance, SpecMatchesTheRegistrationTableAndReportTable3) {
  const std::string id = GetParam();
  const auto expected = expected_specs().find(id);
  ASSERT_NE(expected, expected_specs().end()) << id << " is not one of the 16 benchmark ids or their fork variants";
  const auto env = make(id);
  const EnvSpec& spec = env->spec();
  EXPECT_EQ(spec.id, id);
  EXPECT_EQ(spec.observation_dim, expected->second.observation_dim);
  EXPECT_EQ(spec.action_dim, expected->second.action_dim);
  EXPECT_EQ(spec.max_episode_steps, expected->second.max_episode_steps);
  EXPECT_EQ(spec.cost_limit, expected->second.cost_limit);
  EXPECT_EQ(spec.action_low, -1);
  EXPECT_EQ(spec.action_high, 1);
  EXPECT_EQ(spec.observation_bound, 1000);
  EXPECT_TRUE("Safety" + spec.agent + spec.task + "-v0" == id || "Safety" + spec.agent + spec.task + "-fork" == id);
  EXPECT_EQ(env->reset(1).size(), static_cast<size_t>(spec.observation_dim));
}

// The spec names the cost terms before any step; a step reports the same
// names in the same order (docs/environments.md#tasks lists them per task).
TEST_P(Conformance, SpecNamesTheCostTermsAStepReports) {
  const auto env = make(GetParam());
  const std::map<std::string, std::vector<std::string>> terms_of_task{
      {"Circle", {"cost_outside_bounds"}},
      {"Gather", {"cost_gathered_bombs", "cost_out_of_range"}},
      {"Reach", {"number_collisions", "cost_collisions", "cost_out_of_range"}},
      {"Run", {"cost_outside_bounds", "cost_velocity_violation"}}};
  EXPECT_EQ(env->spec().cost_term_names, terms_of_task.at(env->spec().task));
  env->reset(3);
  const StepResult result = env->step(std::vector<double>(static_cast<size_t>(env->spec().action_dim), 0.0));
  std::vector<std::string> stepped;
  for (const CostTerm& term : result.cost_terms) stepped.emplace_back(term.name);
  EXPECT_EQ(stepped, env->spec().cost_term_names);
}

TEST_P(Conformance, RandomEpisodeKeepsInvariantsAndTruncatesAtTheEpisodeLength) {
  const auto env = make(GetParam());
  const EnvSpec& spec = env->spec();
  // The original's bound of 5 holds where spawns keep their clearance; the fork's Reach may
  // spawn the agent inside the Box (docs/environments.md#the-fork-variant), which throws it out
  // at tens of m/s.
  const bool bounded = describe(GetParam()).obstacle_clearance_from != "stale";
  Rng rng(123);
  for (const uint64_t seed : {11u, 12u}) {
    const std::span<const double> first = env->reset(seed);
    ASSERT_EQ(first.size(), static_cast<size_t>(spec.observation_dim));
    for (double value : first) ASSERT_TRUE(std::isfinite(value));
    int steps = 0;
    bool done = false;
    while (!done) {
      const StepResult result = env->step(random_action(rng, spec.action_dim));
      ++steps;
      ASSERT_EQ(result.observation.size(), static_cast<size_t>(spec.observation_dim));
      for (size_t i = 0; i < result.observation.size(); ++i) {
        const double value = result.observation[i];
        ASSERT_TRUE(std::isfinite(value)) << "obs[" << i << "] at step " << steps;
        if (bounded) {
          ASSERT_LT(std::abs(value), 5.0) << "obs[" << i << "] at step " << steps;
        }
      }
      ASSERT_TRUE(std::isfinite(result.reward)) << "step " << steps;
      ASSERT_TRUE(result.cost == 0.0 || result.cost == 1.0) << result.cost;
      double term_sum = 0;
      for (const CostTerm& term : result.cost_terms) {
        ASSERT_TRUE(std::isfinite(term.value)) << term.name;
        ASSERT_GE(term.value, 0) << term.name;
        term_sum += term.value;
      }
      ASSERT_EQ(result.cost, std::min(1.0, term_sum)) << "cost = min(1, sum of terms)";
      ASSERT_FALSE(result.terminated && result.truncated);
      ASSERT_EQ(result.truncated, steps == spec.max_episode_steps && !result.terminated)
          << "step " << steps;
      done = result.terminated || result.truncated;
      ASSERT_LE(steps, spec.max_episode_steps);
    }
    if (spec.agent == "Ball" || spec.agent == "Car") {
      EXPECT_EQ(steps, spec.max_episode_steps) << "Ball and Car never die (docs/environments.md#termination-and-truncation)";
    }
  }
}

TEST_P(Conformance, SameSeedAndActionsGiveBitIdenticalResultsInTwoInstances) {
  // Two fresh instances see the same sequence of calls.
  const auto c = make(GetParam());
  const auto d = make(GetParam());
  const int steps = std::min(300, c->spec().max_episode_steps);
  for (const uint64_t seed : {5u, 6u}) {
    const std::span<const double> obs_c = c->reset(seed);
    const std::vector<double> first_c(obs_c.begin(), obs_c.end());
    const std::span<const double> obs_d = d->reset(seed);
    ASSERT_TRUE(std::equal(first_c.begin(), first_c.end(), obs_d.begin(), obs_d.end()));
    Rng rng(seed);
    for (int t = 0; t < steps; ++t) {
      const std::vector<double> action = random_action(rng, c->spec().action_dim);
      const StepResult rc = c->step(action);
      const std::vector<double> obs(rc.observation.begin(), rc.observation.end());
      const double reward = rc.reward, cost = rc.cost;
      const bool end_c = rc.terminated || rc.truncated;
      const StepResult rd = d->step(action);
      ASSERT_TRUE(std::equal(obs.begin(), obs.end(), rd.observation.begin(), rd.observation.end()))
          << "step " << t;
      ASSERT_EQ(reward, rd.reward) << "step " << t;  // bit-identical, not near
      ASSERT_EQ(cost, rd.cost) << "step " << t;
      ASSERT_EQ(end_c, rd.terminated || rd.truncated);
      if (end_c) break;
    }
  }
  // reset() without a seed continues the stream identically as well.
  const std::span<const double> next_c = c->reset();
  const std::vector<double> copy(next_c.begin(), next_c.end());
  const std::span<const double> next_d = d->reset();
  EXPECT_TRUE(std::equal(copy.begin(), copy.end(), next_d.begin(), next_d.end()));
}

TEST_P(Conformance, DifferentSeedsGiveDifferentLayouts) {
  const auto env = make(GetParam());
  const std::span<const double> first = env->reset(1);
  const std::vector<double> copy(first.begin(), first.end());
  const std::span<const double> second = env->reset(2);
  EXPECT_FALSE(std::equal(copy.begin(), copy.end(), second.begin(), second.end()));
}

TEST_P(Conformance, WrongSizeActionIsRejectedNamingBothSizes) {
  const auto env = make(GetParam());
  env->reset(0);
  const int dim = env->spec().action_dim;
  const std::vector<double> too_long(static_cast<size_t>(dim + 1), 0.0);
  try {
    env->step(too_long);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(std::to_string(dim + 1)), std::string::npos) << message;
    EXPECT_NE(message.find("expected " + std::to_string(dim)), std::string::npos) << message;
  }
  EXPECT_THROW(env->step(std::vector<double>{}), std::invalid_argument);
}

TEST_P(Conformance, NonFiniteActionIsRejected) {
  const auto env = make(GetParam());
  env->reset(0);
  const auto dim = static_cast<size_t>(env->spec().action_dim);
  for (const double bad : {std::numeric_limits<double>::quiet_NaN(),
                           std::numeric_limits<double>::infinity(),
                           -std::numeric_limits<double>::infinity()}) {
    std::vector<double> action(dim, 0.0);
    action[dim - 1] = bad;
    EXPECT_THROW(env->step(action), std::invalid_argument) << bad;
  }
}

TEST_P(Conformance, StepBeforeResetIsAnError) {
  const auto env = make(GetParam());
  const std::vector<double> action(static_cast<size_t>(env->spec().action_dim), 0.0);
  EXPECT_THROW(env->step(action), std::logic_error);
}

TEST_P(Conformance, InjectingTheSampledLayoutReproducesTheReset) {
  // layout() returns what the last reset placed; reset_to() with it on a fresh
  // instance gives the same reset observation.
  const auto sampled = make(GetParam());
  const std::span<const double> obs = sampled->reset(42);
  const std::vector<double> expected(obs.begin(), obs.end());
  const auto injected = make(GetParam());
  const std::span<const double> again = injected->reset_to(sampled->layout());
  EXPECT_TRUE(std::equal(expected.begin(), expected.end(), again.begin(), again.end()));
}

INSTANTIATE_TEST_SUITE_P(EveryRegisteredEnv, Conformance, ::testing::ValuesIn(registered_ids()),
                         [](const auto& info) {
                           std::string name = info.param;
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });

TEST(Registry, UnknownIdIsAnErrorListingEveryValidId) {
  try {
    make("SafetyBallDance-v0");
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("SafetyBallDance-v0"), std::string::npos) << message;
    for (const std::string& id : registered_ids()) {
      EXPECT_NE(message.find(id), std::string::npos) << id << " missing from: " << message;
    }
  }
}

TEST(Registry, IdsAreSortedAndContainTheFourBallEnvironments) {
  const std::vector<std::string> ids = registered_ids();
  EXPECT_TRUE(std::is_sorted(ids.begin(), ids.end()));
  for (const char* id : {"SafetyBallCircle-v0", "SafetyBallGather-v0", "SafetyBallReach-v0",
                         "SafetyBallRun-v0"}) {
    EXPECT_NE(std::find(ids.begin(), ids.end(), id), ids.end()) << id;
  }
}

}  // namespace
}  // namespace bsg::envs
