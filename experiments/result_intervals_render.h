// The interval estimates of result_intervals.h, training_intervals.h and
// cost_limit_frontier.h as CSV files beside table1.csv and as a Markdown
// summary (`bsg table --ci`). Every CSV has its confidence level in a column,
// so that a file read alone says what its intervals are.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "experiments/cost_limit_frontier.h"
#include "experiments/result_intervals.h"
#include "experiments/training_intervals.h"

namespace bsg::experiments {

std::string interval_rows_csv(const std::vector<IntervalRow>& rows, double confidence);
std::string difference_rows_csv(const std::vector<DifferenceRow>& rows, double confidence);
std::string profile_rows_csv(const std::vector<ProfileRow>& rows, double confidence);
std::string curve_rows_csv(const std::vector<CurveRow>& rows, double confidence);
std::string frontier_csv(const CostLimitFrontier& frontier, double confidence);

// Per environment and column, the selected configuration's IQM of J / J_TRPO (or
// J without TRPO) and of H / d with their intervals and P(feasible); then
// across environments; the pairs distinguishable at the confidence level; the
// training-safety aggregates and the frontier, if given; then the notes.
std::string intervals_markdown(const ResultIntervals& intervals, const TrainingIntervals& training,
                               const std::optional<CostLimitFrontier>& frontier);

// The files written by write_interval_files, in order.
std::vector<std::string> interval_file_names(bool with_frontier);

// intervals.csv, aggregates.csv, distinguishable.csv, profiles.csv,
// training_safety.csv, curves.csv, table1_ci.md and (with a frontier)
// frontier.csv, each atomically, into `out_dir`.
void write_interval_files(const ResultIntervals& intervals, const TrainingIntervals& training,
                          const std::optional<CostLimitFrontier>& frontier, const std::filesystem::path& out_dir);

}  // namespace bsg::experiments
