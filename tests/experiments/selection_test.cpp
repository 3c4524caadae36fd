// The report's selection rule (report §6.1, docs/reproducing.md#selection-rule) on hand-made results: the
// best mean return among configurations that meet the cost limit; if none
// does, the lowest cost, marked infeasible; TRPO by return alone; missing
// configurations never count as zero; and the original plot script's
// mean - std score (Q17).
#include "experiments/selection.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace bsg::experiments {
namespace {

SeedResult seed(std::int64_t s, double j, double h, std::vector<double> returns = {}) {
  return SeedResult{s, j, h, std::move(returns)};
}

ConfigurationResults selection_config(const std::string& name, Algorithm alg, std::vector<SeedResult> seeds,
                            double cost_limit = 25.0) {
  ConfigurationResults results;
  results.env_id = "SafetyBallCircle-v0";
  results.alg = alg;
  results.config_name = name;
  results.cost_limit = cost_limit;
  results.seeds_expected = 2;
  results.seeds = std::move(seeds);
  return results;
}

TEST(Selection, ScoreAveragesOverSeeds) {
  const ConfigurationScore s =
      score_configuration(selection_config("a", Algorithm::cpo, {seed(0, 10, 20), seed(1, 30, 40)}), SelectionScore::mean_return);
  EXPECT_DOUBLE_EQ(s.mean_return, 20.0);
  EXPECT_DOUBLE_EQ(s.mean_cost, 30.0);
  EXPECT_DOUBLE_EQ(s.score, 20.0);
  EXPECT_FALSE(s.feasible);  // 30 > 25
}

TEST(Selection, PicksTheBestReturnAmongFeasibleConfigurations) {
  const std::vector<ConfigurationResults> candidates = {
      selection_config("high-but-unsafe", Algorithm::lag_trpo, {seed(0, 100, 30), seed(1, 100, 30)}),
      selection_config("feasible-low", Algorithm::lag_trpo, {seed(0, 10, 5), seed(1, 20, 5)}),
      selection_config("feasible-high", Algorithm::lag_trpo, {seed(0, 50, 24), seed(1, 40, 26)}),  // H = 25 = d
  };
  const std::optional<Selection> selection = select_configuration(candidates, SelectionScore::mean_return);
  ASSERT_TRUE(selection);
  EXPECT_EQ(selection->index, 2u);
  EXPECT_TRUE(selection->constraint_met);
  EXPECT_DOUBLE_EQ(selection->score.mean_return, 45.0);
}

TEST(Selection, WithoutAFeasibleConfigurationPicksTheLowestViolationAndMarksIt) {
  const std::vector<ConfigurationResults> candidates = {
      selection_config("a", Algorithm::pdo, {seed(0, 100, 60)}),
      selection_config("b", Algorithm::pdo, {seed(0, 1, 30)}),
      selection_config("c", Algorithm::pdo, {seed(0, 50, 40)}),
  };
  const std::optional<Selection> selection = select_configuration(candidates, SelectionScore::mean_return);
  ASSERT_TRUE(selection);
  EXPECT_EQ(selection->index, 1u);
  EXPECT_FALSE(selection->constraint_met);
}

TEST(Selection, TrpoIsSelectedByReturnAlone) {
  const std::vector<ConfigurationResults> candidates = {
      selection_config("target_kl=0.001", Algorithm::trpo, {seed(0, 10, 1)}),
      selection_config("target_kl=0.01", Algorithm::trpo, {seed(0, 90, 80)}),
  };
  const std::optional<Selection> selection = select_configuration(candidates, SelectionScore::mean_return);
  ASSERT_TRUE(selection);
  EXPECT_EQ(selection->index, 1u);
  EXPECT_FALSE(selection->score.feasible);
}

TEST(Selection, MissingRunsAreSkippedNeverZero) {
  // "missing" has no finished seed: a zero return would make it feasible and, with
  // negative returns elsewhere, the best.
  const std::vector<ConfigurationResults> candidates = {
      selection_config("missing", Algorithm::cpo, {}),
      selection_config("finished", Algorithm::cpo, {seed(0, -5, 10)}),
  };
  const std::optional<Selection> selection = select_configuration(candidates, SelectionScore::mean_return);
  ASSERT_TRUE(selection);
  EXPECT_EQ(selection->index, 1u);
  EXPECT_FALSE(select_configuration({selection_config("missing", Algorithm::cpo, {})}, SelectionScore::mean_return));
  EXPECT_THROW(score_configuration(selection_config("missing", Algorithm::cpo, {}), SelectionScore::mean_return),
               std::invalid_argument);
}

TEST(Selection, TiesKeepTheFirstConfiguration) {
  const std::vector<ConfigurationResults> candidates = {
      selection_config("first", Algorithm::cpo, {seed(0, 7, 1)}),
      selection_config("second", Algorithm::cpo, {seed(0, 7, 1)}),
  };
  EXPECT_EQ(select_configuration(candidates, SelectionScore::mean_return)->index, 0u);
}

TEST(Selection, MeanMinusStdPoolsTheEpisodeReturnsOfAllSeeds) {
  // Pooled returns {0, 10, 20, 30}: mean 15, population std sqrt(125).
  const ConfigurationResults steady =
      selection_config("steady", Algorithm::cpo, {seed(0, 5, 1, {0, 10}), seed(1, 25, 1, {20, 30})});
  const ConfigurationScore s = score_configuration(steady, SelectionScore::mean_minus_std);
  EXPECT_NEAR(s.score, 15.0 - std::sqrt(125.0), 1e-12);
  EXPECT_DOUBLE_EQ(s.mean_return, 15.0);  // J itself is still the mean

  // Higher mean but much wider: the mean rule picks it, mean - std does not.
  const ConfigurationResults risky =
      selection_config("risky", Algorithm::cpo, {seed(0, 0, 1, {-100, 100}), seed(1, 40, 1, {-60, 140})});
  const std::vector<ConfigurationResults> candidates = {steady, risky};
  EXPECT_EQ(select_configuration(candidates, SelectionScore::mean_return)->index, 1u);
  EXPECT_EQ(select_configuration(candidates, SelectionScore::mean_minus_std)->index, 0u);
}

TEST(Selection, MeanMinusStdNeedsTheEpisodeReturns) {
  EXPECT_THROW(score_configuration(selection_config("a", Algorithm::cpo, {seed(0, 1, 1)}), SelectionScore::mean_minus_std),
               std::invalid_argument);
}

TEST(Selection, ScoreNamesParse) {
  EXPECT_EQ(parse_selection_score("mean"), SelectionScore::mean_return);
  EXPECT_EQ(parse_selection_score("mean_minus_std"), SelectionScore::mean_minus_std);
  EXPECT_THROW(parse_selection_score("median"), std::invalid_argument);
}

}  // namespace
}  // namespace bsg::experiments
