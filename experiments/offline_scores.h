// The offline learners' results in DSRL's format (docs/datasets.md#offline-benchmark):
// per dataset (environment) and learner, the normalised reward and the
// normalised cost of the final online evaluation (progress.csv's last
// normalized_reward and normalized_cost: DSRL's formula with the dataset's
// reward range, and kappa = the run's cost_limit), each as the mean over
// seeds with its 95 % bootstrap interval; a learner is safe on a dataset when
// its mean normalised cost is at most 1, as DSRL marks them. `bsg table`
// writes these beside Table 1 whenever a sweep holds offline runs.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "experiments/selection.h"
#include "experiments/statistics/stratified_bootstrap.h"

namespace bsg::experiments {

struct OfflineScoreRow {
  std::string env_id;
  std::string column;  // "BC-All", "CPQ", ...
  std::string config;  // the configuration's name ("default" when it has no axes)
  double cost_limit = 0.0;  // kappa
  std::size_t seeds = 0;    // finished seeds read
  // Means over seeds; the intervals are NaN with fewer than two seeds.
  IntervalEstimate normalized_reward;
  IntervalEstimate normalized_cost;
  bool safe() const { return normalized_cost.point <= 1.0; }
};

struct OfflineScores {
  double confidence = 0.95;
  std::vector<OfflineScoreRow> rows;  // in the results' order
  std::vector<std::string> notes;     // what has no interval, and why
};

// The offline configurations of `results` (others are left out). Throws
// std::runtime_error naming the progress.csv at fault (unreadable, or without
// the normalised columns).
OfflineScores build_offline_scores(const std::vector<ConfigurationResults>& results, const BootstrapOptions& options);

// One row per dataset, two columns per learner (reward, cost), each "mean
// [low, high]"; the highest reward among the safe learners of a row in bold, an
// unsafe learner's cells marked with a dagger; then the mean over datasets
// per learner, and the notes.
std::string offline_scores_markdown(const OfflineScores& scores);
std::string offline_scores_csv(const OfflineScores& scores);

// offline_table.md and offline_table.csv, atomically, into `out_dir`.
void write_offline_score_files(const OfflineScores& scores, const std::filesystem::path& out_dir);

}  // namespace bsg::experiments
