// The selection rule with several constraints (docs/reproducing.md#selection-rule): a
// configuration is feasible only when the seed mean of every constraint's H_i
// is within its d_i, and the training cost rate is averaged over seeds; an
// evaluation.json with a constraints list is read back.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "../test_support.h"
#include "experiments/run_results.h"
#include "experiments/selection.h"
#include "experiments/table1.h"
#include "experiments/table1_render.h"

namespace bsg::experiments {
namespace {

ConfigurationResults two_constraint_configuration(std::vector<std::vector<double>> seed_costs) {
  ConfigurationResults config;
  config.env_id = "SafetyBallRun-v0";
  config.alg = Algorithm::cpo;
  config.config_name = std::string("two_constraints");
  config.cost_limit = 25.0;
  config.constraint_limits = {20.0, 5.0};
  for (std::size_t s = 0; s < seed_costs.size(); ++s) {
    config.seeds.push_back({static_cast<std::int64_t>(s), 100.0 + s, 10.0, {}, 0.1 * (s + 1), seed_costs[s]});
  }
  return config;
}

TEST(SeveralConstraintsSelection, FeasibleOnlyWhenEveryConstraintHoldsOnAverage) {
  // Seed means: H_1 = (10 + 20) / 2 = 15 <= 20; H_2 = (4 + 7) / 2 = 5.5 > 5: infeasible,
  // although the single summed H = 10 is within cost_limit 25.
  const ConfigurationScore violated =
      score_configuration(two_constraint_configuration({{10.0, 4.0}, {20.0, 7.0}}), SelectionScore::mean_return);
  EXPECT_EQ(violated.mean_constraint_costs, (std::vector<double>{15.0, 5.5}));
  EXPECT_FALSE(violated.feasible);
  EXPECT_NEAR(violated.mean_cost_rate, 0.15, 1e-15);
  // H_2 = (4 + 6) / 2 = 5 <= 5: both hold.
  EXPECT_TRUE(score_configuration(two_constraint_configuration({{10.0, 4.0}, {20.0, 6.0}}),
                                  SelectionScore::mean_return)
                  .feasible);
  // Selection falls back to the least violating when none is feasible.
  const std::vector<ConfigurationResults> candidates = {
      two_constraint_configuration({{10.0, 9.0}}), two_constraint_configuration({{30.0, 1.0}})};
  const std::optional<Selection> selection = select_configuration(candidates, SelectionScore::mean_return);
  ASSERT_TRUE(selection.has_value());
  EXPECT_FALSE(selection->constraint_met);
}

TEST(SeveralConstraintsSelection, ASeedWithoutEveryConstraintIsAnError) {
  EXPECT_THROW(score_configuration(two_constraint_configuration({{10.0}}), SelectionScore::mean_return),
               std::invalid_argument);
}

TEST(SeveralConstraintsSelection, EvaluationJsonConstraintsAreRead) {
  testing::TemporaryDirectory dir;
  testing::write_text_file(
      dir.path() / "evaluation.json",
      "{\n  \"mean_return\": 1.5,\n  \"mean_cost\": 2,\n  \"episodes\": 4,\n  \"mean_length\": 200,\n"
      "  \"cumulative_cost\": 30,\n  \"cost_rate\": 0.25,\n  \"constraints\": [\n"
      "    {\"terms\": [\"a\"], \"limit\": 20, \"mean_cost\": 3.5, \"holds\": true},\n"
      "    {\"terms\": \"all\", \"limit\": 5, \"mean_cost\": null, \"holds\": null}\n  ]\n}\n");
  const std::optional<RecordedEvaluation> evaluation = read_run_evaluation(algos::RunDirectory(dir.path()));
  ASSERT_TRUE(evaluation.has_value());
  EXPECT_EQ(evaluation->cost_rate, 0.25);
  ASSERT_EQ(evaluation->constraint_costs.size(), 2u);
  EXPECT_EQ(evaluation->constraint_costs[0], 3.5);
  EXPECT_TRUE(std::isnan(evaluation->constraint_costs[1]));
  EXPECT_EQ(evaluation->constraint_limits, (std::vector<double>{20.0, 5.0}));
}

TEST(SeveralConstraintsSelection, TheCostRateMetricShowsTheTrainingCostRateBesideJAndH) {
  ConfigurationResults trpo = two_constraint_configuration({{10.0, 4.0}, {20.0, 6.0}});  // rates 0.1, 0.2
  trpo.alg = Algorithm::trpo;
  trpo.constraint_limits.clear();
  for (SeedResult& seed : trpo.seeds) seed.constraint_costs.clear();
  const ConfigurationResults cpo = two_constraint_configuration({{10.0, 4.0}, {20.0, 6.0}});
  Table1 table = build_table1({trpo, cpo}, SelectionScore::mean_return);
  EXPECT_EQ(table1_markdown(table).find("r="), std::string::npos);  // not by default
  table.show_cost_rate = true;
  const std::string markdown = table1_markdown(table);
  EXPECT_TRUE(testing::contains(markdown, "r=0.15"));  // (0.1 + 0.2) / 2
  EXPECT_TRUE(testing::contains(markdown, "training cost rate"));
}

}  // namespace
}  // namespace bsg::experiments
