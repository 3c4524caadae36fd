// Safety during training and learning curves, with intervals across seeds
// (docs/reproducing.md#safety-during-training), from the progress.csv of each
// finished seed:
// - per configuration: the cumulative training cost at the end, the training
//   cost rate (cumulative cost / steps, Safety Gym's) and the fraction of epochs
//   whose mean episode cost exceeded the limit d, each as mean, median and IQM
//   with its bootstrap interval; with several constraints, each constraint's own
//   (constraint_<i>_...);
// - per Table 1 column, across environments (the selected configurations;
//   one stratum per environment): the fraction of epochs over the limit, as
//   mean, median and IQM with stratified bootstrap intervals (environment
//   empty in those rows);
// - per selected configuration (Figure 2's lines): the mean over seeds of the
//   episode return, episode cost, cost rate and cumulative cost at every epoch,
//   with a pointwise bootstrap band of that mean instead of +- one standard
//   deviation (seeds resampled as whole curves, epochs cut to the shortest seed).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "experiments/result_intervals.h"

namespace bsg::experiments {

struct CurveRow {
  std::string env_id;
  std::string column;
  std::string config;
  std::string metric;  // return, cost, cost_rate, cumulative_cost
  std::size_t epoch = 0;
  std::size_t seeds = 0;
  IntervalEstimate mean;  // the mean over seeds and its band
};

struct TrainingIntervals {
  std::vector<IntervalRow> safety;             // per configuration
  std::vector<IntervalRow> safety_aggregates;  // per column across environments
  std::vector<CurveRow> curves;
  std::vector<std::string> notes;
};

// Throws std::runtime_error naming a progress.csv that cannot be read.
TrainingIntervals build_training_intervals(const std::vector<ConfigurationResults>& results, const Table1& table,
                                           const BootstrapOptions& options);

}  // namespace bsg::experiments
