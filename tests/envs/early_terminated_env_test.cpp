// EarlyTerminatedEnv (envs/early_terminated_env.h): the learner's episode is cut at the step
// where a constraint's episode cost first exceeds its limit, on scripted cost sequences.
#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "cost_script_env.h"
#include "envs/early_terminated_env.h"

namespace bsg::envs {
namespace {

using testing::CostScriptEnv;
using testing::term_budgets;

TEST(EarlyTerminatedEnv, CutsAtTheFirstStepWhoseEpisodeCostExceedsTheLimit) {
  // Costs 1, 1, 0, 1, 0: sums 1, 2, 2, 3 > 2 at step 4 (reaching the limit is no cut).
  EarlyTerminatedEnv env(
      std::make_unique<CostScriptEnv>(std::vector<std::array<double, 2>>{{1, 0}, {1, 0}, {0, 0}, {1, 0}, {0, 0}}),
      term_budgets({2.0}));
  EXPECT_EQ(env.spec().observation_dim, 2);
  env.reset(3);
  for (int t = 1; t <= 4; ++t) {
    const StepResult step = env.step(std::vector<double>{0.0});
    ASSERT_TRUE(step.learner.has_value());
    EXPECT_EQ(step.learner->terminated, t == 4) << t;
    EXPECT_EQ(step.learner->budget_spent, t == 4) << t;
    EXPECT_EQ(step.learner->reward, t == 4 ? 0.0 : 10.0 + t) << t;
    EXPECT_EQ(step.reward, 10.0 + t) << "the environment's reward stays";
    EXPECT_FALSE(step.terminated) << "the environment's episode goes on";
  }
  env.reset();
  EXPECT_EQ(env.episode_costs(), std::vector<double>{0.0});
  EXPECT_FALSE(env.step(std::vector<double>{0.0}).learner->terminated) << "the sum restarts at a reset";
}

TEST(EarlyTerminatedEnv, AnyConstraintsBudgetCuts) {
  // Budget 1 (term a) limit 5 never spent; budget 2 (term b) limit 0 spent by its first cost, at step 2.
  EarlyTerminatedEnv env(std::make_unique<CostScriptEnv>(std::vector<std::array<double, 2>>{{1, 0}, {1, 0.5}, {0, 0}}),
                         term_budgets({5.0, 0.0}));
  env.reset(0);
  EXPECT_FALSE(env.step(std::vector<double>{0.0}).learner->terminated);
  EXPECT_TRUE(env.step(std::vector<double>{0.0}).learner->terminated);
  EXPECT_EQ(env.episode_costs(), (std::vector<double>{2.0, 0.5}));
}

}  // namespace
}  // namespace bsg::envs
