// The cost-limit frontier from hand-made results over two limits: one point
// per limit with the seeds' mean J and H, families without their cost_limit
// item, several constraints as panels, and clear refusals.
#include "experiments/cost_limit_frontier.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

namespace bsg::experiments {
namespace {

ConfigurationResults frontier_config(Algorithm alg, const std::string& name, double d, std::vector<SeedResult> seeds) {
  ConfigurationResults results;
  results.env_id = "SafetyBallCircle-v0";
  results.alg = alg;
  results.config_name = name;
  results.cost_limit = d;
  results.seeds_expected = seeds.size();
  results.seeds = std::move(seeds);
  return results;
}

TEST(CostLimitFrontier, FamiliesAreConfigurationsWithoutTheirLimit) {
  EXPECT_EQ(frontier_family("lambda_optimizer=PID,cost_limit=10"), "lambda_optimizer=PID");
  EXPECT_EQ(frontier_family("cost_limit=10"), "default");
  EXPECT_EQ(frontier_family("cost_limit=10,target_kl=0.01"), "target_kl=0.01");
  EXPECT_EQ(frontier_family("default"), "default");
}

TEST(CostLimitFrontier, OnePointPerLimitSortedByTheLimit) {
  const std::vector<ConfigurationResults> results = {
      frontier_config(Algorithm::lag_trpo, "cost_limit=25", 25.0, {{0, 300, 20, {}}, {1, 310, 30, {}}}),
      frontier_config(Algorithm::lag_trpo, "cost_limit=5", 5.0, {{0, 100, 4, {}}, {1, 120, 8, {}}}),
  };
  const CostLimitFrontier frontier = build_cost_limit_frontier(results, {});
  ASSERT_EQ(frontier.points.size(), 2u);
  EXPECT_DOUBLE_EQ(frontier.points[0].cost_limit, 5.0);
  EXPECT_DOUBLE_EQ(frontier.points[0].mean_return.point, 110.0);
  EXPECT_DOUBLE_EQ(frontier.points[0].mean_cost.point, 6.0);
  EXPECT_DOUBLE_EQ(frontier.points[0].feasible.point, 0.5);  // 4 <= 5, 8 > 5
  EXPECT_DOUBLE_EQ(frontier.points[1].cost_limit, 25.0);
  EXPECT_DOUBLE_EQ(frontier.points[1].mean_return.point, 305.0);
  EXPECT_EQ(frontier.points[1].column, "TRPO-L");
  EXPECT_EQ(frontier.points[1].family, "default");
  EXPECT_LE(frontier.points[1].mean_cost.low, 25.0);
  EXPECT_GE(frontier.points[1].mean_cost.high, 25.0);  // the interval of {20, 30} reaches both
}

TEST(CostLimitFrontier, SeveralConstraintsGiveOnePanelEach) {
  ConfigurationResults low = frontier_config(Algorithm::cpo, "limits=low", 25.0, {{0, 10, 3, {}, 0.0, {1, 2}}, {1, 12, 5, {}, 0.0, {3, 2}}});
  low.constraint_limits = {2, 1};
  ConfigurationResults high = frontier_config(Algorithm::cpo, "limits=high", 25.0, {{0, 20, 9, {}, 0.0, {5, 4}}, {1, 22, 9, {}, 0.0, {5, 4}}});
  high.constraint_limits = {10, 5};
  // Different names: two families of one limit each, unless named alike.
  low.config_name = high.config_name = "default";
  low.config_dir = "a";
  high.config_dir = "b";
  const CostLimitFrontier frontier = build_cost_limit_frontier({low, high}, {});
  ASSERT_EQ(frontier.points.size(), 4u);  // 2 constraints x 2 limit sets
  EXPECT_EQ(frontier.points[0].constraint, 1u);
  EXPECT_DOUBLE_EQ(frontier.points[0].cost_limit, 2.0);
  EXPECT_DOUBLE_EQ(frontier.points[0].mean_cost.point, 2.0);  // H_1 = 1, 3
  EXPECT_DOUBLE_EQ(frontier.points[0].feasible.point, 0.0);   // seed 0: H_2 = 2 > 1; seed 1: H_1 = 3 > 2
  EXPECT_EQ(frontier.points[2].constraint, 2u);
  EXPECT_DOUBLE_EQ(frontier.points[2].cost_limit, 1.0);
  EXPECT_DOUBLE_EQ(frontier.points[3].feasible.point, 1.0);   // 5 <= 10 and 4 <= 5
}

TEST(CostLimitFrontier, OneLimitOrOneSeedIsRefusedNamingTheLimits) {
  const std::vector<ConfigurationResults> one_limit = {
      frontier_config(Algorithm::lag_trpo, "default", 25.0, {{0, 300, 20, {}}, {1, 310, 30, {}}}),
  };
  try {
    build_cost_limit_frontier(one_limit, {});
    FAIL() << "a frontier of one limit";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("the sweep's limits: 25"), std::string::npos) << error.what();
  }
  const std::vector<ConfigurationResults> one_seed = {
      frontier_config(Algorithm::lag_trpo, "cost_limit=5", 5.0, {{0, 100, 4, {}}}),
      frontier_config(Algorithm::lag_trpo, "cost_limit=25", 25.0, {{0, 300, 20, {}}}),
  };
  EXPECT_THROW(build_cost_limit_frontier(one_seed, {}), std::invalid_argument);
}

}  // namespace
}  // namespace bsg::experiments
