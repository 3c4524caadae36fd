// SauteEnv (envs/saute_env.h): the budget left and the learner's reward step by step on a
// scripted cost sequence, against values worked out by hand.
#include <gtest/gtest.h>

#include <memory>
#include <stdexcept>
#include <vector>

#include "cost_script_env.h"
#include "envs/saute_env.h"

namespace bsg::envs {
namespace {

using testing::CostScriptEnv;
using testing::term_budgets;

// gamma_s = 1/2 and T = 2 make d~ = d (1 - 1/4) / (1/2 * 2) = 3/4 d: d = 4 gives d~ = 3.
TEST(SauteEnv, TheBudgetLeftAndTheRewardFollowTheHandComputation) {
  // Costs of budget 1 (term a): 1.5, 3, 6, 0.
  SauteEnv env(std::make_unique<CostScriptEnv>(std::vector<std::array<double, 2>>{{1.5, 0}, {3, 0}, {6, 0}, {0, 0}}),
               term_budgets({4.0}), SauteOptions{0.5, -2.5, 2});
  ASSERT_EQ(env.spec().observation_dim, 3);
  ASSERT_EQ(env.normalized_budgets(), std::vector<double>{3.0});
  const std::span<const double> first = env.reset(1);
  EXPECT_EQ(std::vector<double>(first.begin(), first.end()), (std::vector<double>{0, 7, 1}));  // z_0 = 1
  // z_1 = (1 - 1.5/3)/0.5 = 1; z_2 = (1 - 3/3)/0.5 = 0 (spent); z_3 = (0 - 6/3)/0.5 = -4; z_4 = -8.
  const double z[] = {1, 0, -4, -8};
  const bool spent[] = {false, true, true, true};
  for (int t = 0; t < 4; ++t) {
    const StepResult step = env.step(std::vector<double>{0.0});
    ASSERT_EQ(step.observation.size(), 3u);
    EXPECT_EQ(step.observation[0], t + 1.0) << t;
    EXPECT_EQ(step.observation[2], z[t]) << t;
    EXPECT_EQ(env.budgets_left()[0], z[t]) << t;
    EXPECT_EQ(step.reward, 11.0 + t) << "the environment's reward stays";
    EXPECT_EQ(step.cost, step.cost_terms[0].value);
    ASSERT_TRUE(step.learner.has_value());
    EXPECT_EQ(step.learner->reward, spent[t] ? -2.5 : 11.0 + t) << t;
    EXPECT_EQ(step.learner->budget_spent, spent[t]) << t;
    EXPECT_FALSE(step.learner->terminated);
  }
  const std::span<const double> again = env.reset();
  EXPECT_EQ(again[2], 1.0) << "a reset restores the whole budget";
}

TEST(SauteEnv, EachConstraintKeepsItsOwnBudget) {
  // d = (4, 8): d~ = (3, 6). Budget 2's costs 6, 6: z = (1 - 1)/0.5 = 0 at the first step.
  SauteEnv env(std::make_unique<CostScriptEnv>(std::vector<std::array<double, 2>>{{0, 6}, {1.5, 0}}),
               term_budgets({4.0, 8.0}), SauteOptions{0.5, -1.0, 2});
  ASSERT_EQ(env.spec().observation_dim, 4);
  env.reset(0);
  StepResult step = env.step(std::vector<double>{0.0});
  EXPECT_EQ(step.observation[2], 2.0);  // (1 - 0)/0.5
  EXPECT_EQ(step.observation[3], 0.0);  // (1 - 6/6)/0.5
  EXPECT_TRUE(step.learner->budget_spent);
  EXPECT_EQ(step.learner->reward, -1.0);
  step = env.step(std::vector<double>{0.0});
  EXPECT_EQ(step.observation[2], 3.0);  // (2 - 1.5/3)/0.5
  EXPECT_EQ(step.observation[3], 0.0);
  EXPECT_TRUE(step.learner->budget_spent);
}

TEST(SauteEnv, AScheduledBudgetStartsTheNextEpisodesAtItsFraction) {
  // d = 4, d~ = 3 (gamma_s = 1/2, T = 2), costs 1.5 each step. With the whole budget z = 1, 1, 1, ...
  // (z_1 = (1 - 0.5)/0.5); at half of it, z_0 = 1/2 and z_1 = (0.5 - 0.5)/0.5 = 0: spent at once.
  SauteEnv env(std::make_unique<CostScriptEnv>(std::vector<std::array<double, 2>>{{1.5, 0}, {1.5, 0}, {1.5, 0}}),
               term_budgets({4.0}), SauteOptions{0.5, -2.5, 2});
  EXPECT_EQ(env.reset(1)[2], 1.0);
  StepResult step = env.step(std::vector<double>{0.0});
  EXPECT_EQ(step.observation[2], 1.0);
  EXPECT_FALSE(step.learner->budget_spent);
  env.set_start_fractions(std::vector<double>{0.5});
  EXPECT_EQ(env.budgets_left()[0], 1.0) << "the episode under way keeps its budget";
  EXPECT_EQ(env.reset()[2], 0.5);
  step = env.step(std::vector<double>{0.0});
  EXPECT_EQ(step.observation[2], 0.0);
  EXPECT_TRUE(step.learner->budget_spent);
  EXPECT_EQ(step.learner->reward, -2.5);
  EXPECT_EQ(env.reset(2)[2], 0.5) << "every later episode starts at the fraction";
  env.set_start_fractions(std::vector<double>{1.0});
  EXPECT_EQ(env.reset()[2], 1.0);
  // A fraction outside (0, 1] or one per budget missing is refused.
  EXPECT_THROW(env.set_start_fractions(std::vector<double>{0.0}), std::invalid_argument);
  EXPECT_THROW(env.set_start_fractions(std::vector<double>{1.5}), std::invalid_argument);
  EXPECT_THROW(env.set_start_fractions(std::vector<double>{0.5, 0.5}), std::invalid_argument);
}

TEST(SauteEnv, ABudgetItCannotDivideByIsRefused) {
  const auto make = [](double limit, double gamma) {
    return SauteEnv(std::make_unique<CostScriptEnv>(std::vector<std::array<double, 2>>{{0, 0}}), term_budgets({limit}),
                    SauteOptions{gamma, -1.0, 2});
  };
  EXPECT_THROW(make(0.0, 0.5), std::invalid_argument);
  EXPECT_THROW(make(1.0, 1.0), std::invalid_argument);
}

}  // namespace
}  // namespace bsg::envs
