// A sweep's results with their uncertainty across seeds (docs/reproducing.md#intervals):
// for every configuration with at least two finished seeds, J, J / J_TRPO and
// H / d as mean, median and interquartile mean with stratified bootstrap
// intervals, and the probability that a seed meets the limit (Wilson
// interval); across environments, per Table 1 column, the same statistics of
// the selected configurations' seeds pooled, resampled within environments;
// within each environment, the difference between every two columns'
// selected configurations with its interval (distinguishable when it excludes
// 0); and performance profiles of J / J_TRPO and of the feasibility margin
// (d - H) / d. The numerics are experiments/statistics/; this file only
// gathers a sweep's numbers into them.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "experiments/selection.h"
#include "experiments/statistics/stratified_bootstrap.h"
#include "experiments/table1.h"

namespace bsg::experiments {

// One estimate: of a configuration (env_id and config set), or of a column
// across environments (env_id and config empty).
struct IntervalRow {
  std::string env_id;
  std::string column;  // Table 1's label: "TRPO-L", "CPPO-PID", ...
  std::string config;
  std::string config_dir;
  double cost_limit = 0.0;  // d (NaN across environments with different limits)
  bool selected = false;    // the configuration Table 1 selected
  std::size_t environments = 1;
  std::size_t seeds = 0;    // runs in all
  std::string metric;       // J, J_over_trpo, H, H_over_d, feasible, cumulative_cost, ...
  std::string statistic;    // mean, median, iqm, proportion
  IntervalEstimate estimate;
};

// Column a minus column b within one environment (their selected configurations).
struct DifferenceRow {
  std::string env_id;
  std::string metric;  // J or H
  std::string column_a;
  std::string column_b;
  std::size_t seeds_a = 0;
  std::size_t seeds_b = 0;
  IntervalEstimate difference;  // of the means
  bool distinguishable = false;  // the interval excludes 0
};

struct ProfileRow {
  std::string column;
  std::string metric;  // J_over_trpo or feasibility_margin
  std::size_t environments = 0;
  std::size_t seeds = 0;
  double tau = 0.0;
  IntervalEstimate fraction;  // of runs with a score above tau
};

struct ResultIntervals {
  double confidence = 0.95;
  std::vector<IntervalRow> configurations;
  std::vector<IntervalRow> aggregates;
  std::vector<DifferenceRow> differences;
  std::vector<ProfileRow> profiles;
  // What has no interval, and why (one seed, no TRPO to normalise by, ...).
  std::vector<std::string> notes;
};

// `table` is build_table1 of the same results (selection and J_TRPO).
// Throws std::invalid_argument when no configuration has two finished seeds,
// naming the sweep's largest seed count.
ResultIntervals build_result_intervals(const std::vector<ConfigurationResults>& results, const Table1& table,
                                       const BootstrapOptions& options, std::size_t profile_thresholds = 101);

// Shared with the training-safety and frontier builders.
std::string column_label_of(const ConfigurationResults& config);
std::string config_dir_of(const ConfigurationResults& config);
// Whether Table 1 selected this configuration.
bool is_selected(const Table1& table, const ConfigurationResults& config);
// The feasibility of one seed: H <= d, or every H_i <= d_i.
bool seed_feasible(const ConfigurationResults& config, const SeedResult& seed);

}  // namespace bsg::experiments
