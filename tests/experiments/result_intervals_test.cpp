// A sweep's results with intervals, from hand-made results: the normalised
// return J / J_TRPO per seed, H / d, P(H <= d) with its Wilson interval, the
// aggregate across environments, differences between columns, profiles, and a
// clear refusal when no configuration has two seeds.
#include "experiments/result_intervals.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "experiments/result_intervals_render.h"

namespace bsg::experiments {
namespace {

ConfigurationResults interval_config(const std::string& env, Algorithm alg, const std::string& name,
                            std::vector<SeedResult> seeds, double d = 25.0) {
  ConfigurationResults results;
  results.env_id = env;
  results.alg = alg;
  results.config_name = name;
  results.cost_limit = d;
  results.seeds_expected = seeds.size();
  results.seeds = std::move(seeds);
  return results;
}

const IntervalRow& find(const std::vector<IntervalRow>& rows, const std::string& env, const std::string& column,
                        const std::string& metric, const std::string& statistic) {
  for (const IntervalRow& row : rows) {
    if (row.env_id == env && row.column == column && row.metric == metric && row.statistic == statistic) return row;
  }
  throw std::runtime_error("no row " + env + " " + column + " " + metric + " " + statistic);
}

// Two environments; TRPO's selected J is 200 on Circle and 10 on Run.
std::vector<ConfigurationResults> interval_results() {
  const std::string circle = "SafetyBallCircle-v0";
  const std::string run = "SafetyBallRun-v0";
  return {
      interval_config(circle, Algorithm::trpo, "default", {{0, 190, 70, {}}, {1, 210, 90, {}}}),
      interval_config(circle, Algorithm::lag_trpo, "default", {{0, 100, 20, {}}, {1, 120, 24, {}}, {2, 140, 30, {}}}),
      interval_config(run, Algorithm::trpo, "default", {{0, 9, 50, {}}, {1, 11, 50, {}}}),
      interval_config(run, Algorithm::lag_trpo, "default", {{0, 5, 10, {}}, {1, 6, 20, {}}, {2, 7, 40, {}}}),
      interval_config(run, Algorithm::cpo, "default", {{0, 4, 10, {}}}),  // one seed: no interval
  };
}

TEST(ResultIntervals, SeedsAreNormalisedByTrposSelectedReturnAndFeasibilityIsAProportion) {
  const std::vector<ConfigurationResults> all = interval_results();
  const Table1 table = build_table1(all, SelectionScore::mean_return);
  const ResultIntervals intervals = build_result_intervals(all, table, {});
  // Circle TRPO-L: J / 200 = 0.5, 0.6, 0.7: mean 0.6; n = 3 so IQM = mean.
  const IntervalRow& j = find(intervals.configurations, "SafetyBallCircle-v0", "TRPO-L", "J_over_trpo", "iqm");
  EXPECT_NEAR(j.estimate.point, 0.6, 1e-12);
  EXPECT_TRUE(j.selected);
  EXPECT_GE(j.estimate.low, 0.5 - 1e-12);
  EXPECT_LE(j.estimate.high, 0.7 + 1e-12);
  // H / d = 0.8, 0.96, 1.2: median 0.96; 2 of 3 seeds meet d = 25.
  EXPECT_NEAR(find(intervals.configurations, "SafetyBallCircle-v0", "TRPO-L", "H_over_d", "median").estimate.point,
              0.96, 1e-12);
  const IntervalRow& p = find(intervals.configurations, "SafetyBallCircle-v0", "TRPO-L", "feasible", "proportion");
  EXPECT_NEAR(p.estimate.point, 2.0 / 3.0, 1e-12);
  EXPECT_GT(p.estimate.low, 0.0);
  EXPECT_LT(p.estimate.high, 1.0);
  // Across environments: TRPO-L's J / J_TRPO pooled from 0.5, 0.6, 0.7 and 0.5, 0.6, 0.7 (Run: J / 10).
  const IntervalRow& aggregate = find(intervals.aggregates, "", "TRPO-L", "J_over_trpo", "iqm");
  EXPECT_EQ(aggregate.environments, 2u);
  EXPECT_EQ(aggregate.seeds, 6u);
  // n = 6: floor(6 / 4) = 1 cut from each end of 0.5 0.5 0.6 0.6 0.7 0.7: IQM 0.6.
  EXPECT_NEAR(aggregate.estimate.point, 0.6, 1e-12);
  // P(H <= d) pooled: Circle 2 of 3, Run 3 of 3 (10, 20 <= 25; 40 > 25: 2 of 3) -> 4 of 6.
  EXPECT_NEAR(find(intervals.aggregates, "", "TRPO-L", "feasible", "proportion").estimate.point, 4.0 / 6.0, 1e-12);
  // CPO's single seed is named, never given an interval.
  bool named = false;
  for (const std::string& note : intervals.notes) named = named || note.find("SafetyBallRun-v0/cpo/default: 1") == 0;
  EXPECT_TRUE(named);
  for (const IntervalRow& row : intervals.configurations) EXPECT_NE(row.column, "CPO");
}

TEST(ResultIntervals, DifferencesBetweenColumnsAreDistinguishableOnlyWhenTheirIntervalExcludesZero) {
  const std::vector<ConfigurationResults> all = interval_results();
  const ResultIntervals intervals = build_result_intervals(all, build_table1(all, SelectionScore::mean_return), {});
  bool seen_circle_j = false;
  for (const DifferenceRow& row : intervals.differences) {
    if (row.env_id == "SafetyBallCircle-v0" && row.metric == "J") {
      seen_circle_j = true;
      EXPECT_EQ(row.column_a, "TRPO");
      EXPECT_EQ(row.column_b, "TRPO-L");
      EXPECT_NEAR(row.difference.point, 200.0 - 120.0, 1e-12);
      EXPECT_TRUE(row.distinguishable);  // every resample: at least 190 - 140 = 50
    }
    if (row.env_id == "SafetyBallRun-v0" && row.metric == "H") {
      EXPECT_NEAR(row.difference.point, 50.0 - 70.0 / 3.0, 1e-12);
    }
  }
  EXPECT_TRUE(seen_circle_j);
}

TEST(ResultIntervals, ProfilesStartAtOneAndEndAtZero) {
  const std::vector<ConfigurationResults> all = interval_results();
  const ResultIntervals intervals = build_result_intervals(all, build_table1(all, SelectionScore::mean_return), {});
  double first = -1.0;
  double last = -1.0;
  for (const ProfileRow& row : intervals.profiles) {
    if (row.column != "TRPO-L" || row.metric != "J_over_trpo") continue;
    if (first < 0.0) first = row.fraction.point;
    last = row.fraction.point;
  }
  EXPECT_DOUBLE_EQ(first, 1.0);  // the thresholds reach below the lowest score
  EXPECT_DOUBLE_EQ(last, 0.0);   // and above the highest
}

TEST(ResultIntervals, ASweepWithOneSeedIsRefusedWithAClearMessage) {
  const std::vector<ConfigurationResults> one_seed = {
      interval_config("SafetyBallCircle-v0", Algorithm::trpo, "default", {{0, 190, 70, {}}}),
      interval_config("SafetyBallCircle-v0", Algorithm::lag_trpo, "default", {{0, 100, 20, {}}}),
  };
  try {
    build_result_intervals(one_seed, build_table1(one_seed, SelectionScore::mean_return), {});
    FAIL() << "one seed was given intervals";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("needs at least 2"), std::string::npos) << error.what();
  }
}

TEST(ResultIntervals, CsvFilesSayTheirConfidence) {
  const std::vector<ConfigurationResults> all = interval_results();
  BootstrapOptions options;
  options.confidence = 0.9;
  const ResultIntervals intervals = build_result_intervals(all, build_table1(all, SelectionScore::mean_return), options);
  const std::string csv = interval_rows_csv(intervals.configurations, intervals.confidence);
  EXPECT_EQ(csv.substr(0, csv.find('\n')),
            "env_id,column,config,config_dir,cost_limit,selected,environments,seeds,metric,statistic,point,low,high,"
            "confidence");
  EXPECT_NE(csv.find(",0.9\n"), std::string::npos);
}

}  // namespace
}  // namespace bsg::experiments
