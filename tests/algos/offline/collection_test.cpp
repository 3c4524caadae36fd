// The collection (algos/offline/collection.h): the file of a random-policy
// collection, read back, equals a rollout of the same environment stepped
// independently here with the documented seeds; terminals and timeouts sit at
// the steps where the environment ended or cut the episode; shares split the
// episodes by the largest remainder.
#include "algos/offline/collection.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "../../test_support.h"
#include "../scripted_env.h"
#include "algos/offline/dataset_file.h"
#include "common/random.h"
#include "common/run_config.h"
#include "common/seeding.h"

namespace bsg::algos {
namespace {

TEST(Collection, SplitByShares) {
  EXPECT_EQ(split_by_shares(10, {1.0}), (std::vector<std::int64_t>{10}));
  EXPECT_EQ(split_by_shares(10, {1.0, 3.0}), (std::vector<std::int64_t>{3, 7}));  // 2.5, 7.5: tie to the first
  EXPECT_EQ(split_by_shares(10, {1.0, 1.0, 1.0}), (std::vector<std::int64_t>{4, 3, 3}));
  EXPECT_EQ(split_by_shares(7, {0.2, 0.8}), (std::vector<std::int64_t>{1, 6}));  // 1.4, 5.6
  EXPECT_THROW(split_by_shares(10, {1.0, 0.0}), std::invalid_argument);
  EXPECT_THROW(split_by_shares(10, {}), std::invalid_argument);
}

TEST(Collection, RandomPolicyFileEqualsAnIndependentRollout) {
  const std::string id = "SafetyBallCircle-v0";
  std::unique_ptr<envs::Env> env = envs::make(id);
  const int obs = env->spec().observation_dim;
  const int act = env->spec().action_dim;
  std::unique_ptr<CollectionPolicy> random = make_random_policy(act, -1.0, 1.0);
  const std::uint64_t seed = 17;
  const OfflineDataset collected =
      collect_dataset(*env, {{random.get(), 1.0}}, {CollectionUnit::episodes, 2, seed});
  testing::TemporaryDirectory dir("collection");
  write_dataset_file(dir.path() / "d.hdf5", collected);
  const OfflineDataset d = read_dataset_file(dir.path() / "d.hdf5");

  // The oracle: the environment stepped here, episode e reset with
  // derive_seed(seed, environment, 0, e), actions uniform in [-1, 1] from
  // derive_seed(seed, action_noise, 0, e), as collection.h documents.
  std::unique_ptr<envs::Env> oracle = envs::make(id);
  const int T = oracle->spec().max_episode_steps;
  ASSERT_EQ(d.size(), static_cast<std::size_t>(2 * T));
  std::size_t row = 0;
  for (std::uint64_t e = 0; e < 2; ++e) {
    std::span<const double> o = oracle->reset(derive_seed(seed, SeedStream::environment, 0, e));
    std::vector<double> observation(o.begin(), o.end());
    Rng rng(derive_seed(seed, SeedStream::action_noise, 0, e));
    for (int t = 0; t < T; ++t, ++row) {
      std::vector<double> action(static_cast<std::size_t>(act));
      for (double& a : action) a = uniform(rng, -1.0, 1.0);
      const envs::StepResult step = oracle->step(action);
      for (int k = 0; k < obs; ++k) {
        ASSERT_EQ(d.observations[row * obs + k], static_cast<float>(observation[k])) << row;
        ASSERT_EQ(d.next_observations[row * obs + k], static_cast<float>(step.observation[k])) << row;
      }
      for (int k = 0; k < act; ++k) ASSERT_EQ(d.actions[row * act + k], static_cast<float>(action[k])) << row;
      ASSERT_EQ(d.rewards[row], static_cast<float>(step.reward)) << row;
      ASSERT_EQ(d.costs[row], static_cast<float>(step.cost)) << row;
      // Ball never dies: every episode ends by the time limit at its last step.
      ASSERT_EQ(d.terminals[row], 0.0f) << row;
      ASSERT_EQ(d.timeouts[row], t == T - 1 ? 1.0f : 0.0f) << row;
      observation.assign(step.observation.begin(), step.observation.end());
    }
  }
  EXPECT_EQ(d.number_attributes.at("episodes"), 2.0);
  EXPECT_EQ(d.text_attributes.at("seed"), "17");
}

TEST(Collection, TerminalsAndTimeoutsAtTheRightSteps) {
  // Episodes of the scripted environment end by termination after 4 steps
  // (its time limit is 10): terminals at rows 3, 7, 11, no timeouts.
  testing::ScriptedEnv terminating(10, 4);
  std::unique_ptr<CollectionPolicy> random = make_random_policy(2, -1.0, 1.0);
  OfflineDataset d = collect_dataset(terminating, {{random.get(), 1.0}}, {CollectionUnit::episodes, 3, 0});
  ASSERT_EQ(d.size(), 12u);
  for (std::size_t t = 0; t < 12; ++t) {
    EXPECT_EQ(d.terminals[t], t % 4 == 3 ? 1.0f : 0.0f) << t;
    EXPECT_EQ(d.timeouts[t], 0.0f) << t;
  }
  // Time limit 5, no termination, 12 transitions: timeouts at rows 4 and 9
  // (the limit) and 11 (the collection's end cuts the third episode).
  testing::ScriptedEnv truncating(5);
  d = collect_dataset(truncating, {{random.get(), 1.0}}, {CollectionUnit::transitions, 12, 0});
  ASSERT_EQ(d.size(), 12u);
  for (std::size_t t = 0; t < 12; ++t) {
    EXPECT_EQ(d.terminals[t], 0.0f) << t;
    EXPECT_EQ(d.timeouts[t], (t == 4 || t == 9 || t == 11) ? 1.0f : 0.0f) << t;
  }
  // Rewards are 1 + 0.01 k at episode step k: the two whole episodes return
  // 1.01 + ... + 1.05 = 5.15 each; the cut third (1.01 + 1.02 = 2.03) sets no constant.
  EXPECT_NEAR(d.number_attributes.at("max_episode_reward"), 5.15, 1e-5);
  EXPECT_NEAR(d.number_attributes.at("min_episode_reward"), 5.15, 1e-5);
}

TEST(Collection, ConstantsRangeOverWholeEpisodesOnly) {
  testing::ScriptedEnv truncating(5);
  std::unique_ptr<CollectionPolicy> random = make_random_policy(2, -1.0, 1.0);
  // 10 transitions end where the second episode's time limit ends it: both
  // are whole, 5.15 each.
  OfflineDataset d = collect_dataset(truncating, {{random.get(), 1.0}}, {CollectionUnit::transitions, 10, 0});
  EXPECT_NEAR(d.number_attributes.at("min_episode_reward"), 5.15, 1e-5);
  // Two policies of 7 transitions each: each has one whole episode and one
  // cut after 2 rows; only the whole ones count.
  std::unique_ptr<CollectionPolicy> other = make_random_policy(2, -1.0, 1.0);
  d = collect_dataset(truncating, {{random.get(), 1.0}, {other.get(), 1.0}}, {CollectionUnit::transitions, 14, 0});
  ASSERT_EQ(d.size(), 14u);
  EXPECT_NEAR(d.number_attributes.at("min_episode_reward"), 5.15, 1e-5);
  EXPECT_NEAR(d.number_attributes.at("max_episode_reward"), 5.15, 1e-5);
  // 3 transitions: one cut episode and no whole one, so no constants.
  d = collect_dataset(truncating, {{random.get(), 1.0}}, {CollectionUnit::transitions, 3, 0});
  for (const char* key : {"min_episode_reward", "max_episode_reward", "min_episode_cost", "max_episode_cost"}) {
    EXPECT_EQ(d.number_attributes.count(key), 0u) << key;
  }
  EXPECT_EQ(d.number_attributes.at("episodes"), 1.0);
}

TEST(Collection, ActionsAreClippedToTheDeclaredBounds) {
  // A policy that always asks for 3 and -3.
  struct Loud final : CollectionPolicy {
    std::string description() const override { return "loud"; }
    void start_episode(std::uint64_t) override {}
    void act(std::span<const double>, std::span<double> action) override {
      action[0] = 3.0;
      action[1] = -3.0;
    }
  } loud;
  testing::ScriptedEnv env(3);
  const OfflineDataset d = collect_dataset(env, {{&loud, 1.0}}, {CollectionUnit::episodes, 1, 0});
  EXPECT_EQ(d.actions, (std::vector<float>{1, -1, 1, -1, 1, -1}));
}

TEST(Collection, SeveralConstraintsFillTheMatrixAndSumIntoCosts) {
  // A policy that always pushes the ball diagonally, so that it leaves the avenue (|y| > 2) and
  // speeds up: both of BallRun's cost terms are non-zero at some steps.
  struct Diagonal final : CollectionPolicy {
    std::string description() const override { return "diagonal"; }
    void start_episode(std::uint64_t) override {}
    void act(std::span<const double>, std::span<double> action) override {
      action[0] = 1.0;
      action[1] = 1.0;
    }
  } diagonal;
  RunConfig config;
  config.constraints = {{{"cost_outside_bounds"}, 20.0}, {{"cost_velocity_violation"}, 5.0}};
  std::unique_ptr<envs::Env> env = envs::make("SafetyBallRun-v0");
  StepCostSelector costs(config);
  costs.bind(env->spec().cost_term_names, env->spec().id);
  const OfflineDataset d = collect_dataset(*env, {{&diagonal, 1.0}}, {CollectionUnit::episodes, 1, 9}, costs,
                                           {"cost_outside_bounds", "cost_velocity_violation"});
  // The oracle: the same episode stepped here, each term read by its name.
  std::unique_ptr<envs::Env> oracle = envs::make("SafetyBallRun-v0");
  oracle->reset(derive_seed(9, SeedStream::environment, 0, 0));
  ASSERT_EQ(d.constraint_costs.size(), 2 * d.size());
  double outside = 0.0, fast = 0.0;
  for (std::size_t t = 0; t < d.size(); ++t) {
    const envs::StepResult step = oracle->step(std::vector<double>{1.0, 1.0});
    ASSERT_EQ(d.constraint_costs[2 * t], static_cast<float>(step.cost_term("cost_outside_bounds"))) << t;
    ASSERT_EQ(d.constraint_costs[2 * t + 1], static_cast<float>(step.cost_term("cost_velocity_violation"))) << t;
    ASSERT_EQ(d.costs[t], static_cast<float>(step.cost_term("cost_outside_bounds") +
                                             step.cost_term("cost_velocity_violation")))
        << t;
    outside += step.cost_term("cost_outside_bounds");
    fast += step.cost_term("cost_velocity_violation");
  }
  EXPECT_GT(outside, 0.0);
  EXPECT_GT(fast, 0.0);
}

TEST(Collection, RefusesACountBelowOne) {
  testing::ScriptedEnv env(3);
  std::unique_ptr<CollectionPolicy> random = make_random_policy(2, -1.0, 1.0);
  EXPECT_THROW(collect_dataset(env, {{random.get(), 1.0}}, {CollectionUnit::episodes, 0, 0}), std::invalid_argument);
}

}  // namespace
}  // namespace bsg::algos
