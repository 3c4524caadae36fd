// What an offline algorithm learns from: the dataset's training rows (every row, or BC-Safe's rows
// of episodes within the cost limit), their observations' standardisation constants, and minibatches
// of them drawn uniformly with replacement (OSRL's sampler).
#pragma once

#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "algos/offline/offline_algorithm.h"
#include "algos/offline/offline_dataset.h"
#include "common/random.h"

namespace bsg::algos {

struct TrainingRows {
  std::vector<std::size_t> rows;
  std::size_t episodes = 0;  // complete episodes among them (every episode of the dataset for all rows)
};

// Every row of the dataset. Throws std::invalid_argument if it is empty.
TrainingRows all_rows(const OfflineDataset& dataset);
// The rows of the complete episodes whose cost return is at most `cost_limit`. Throws
// std::invalid_argument if there is none.
TrainingRows rows_within_cost_limit(const OfflineDataset& dataset, double cost_limit);

// The mean and standard deviation of each observation feature over `rows`; a feature with standard
// deviation <= 1e-8 keeps the scale 1.
struct ObservationScaling {
  Eigen::VectorXd mean;
  Eigen::VectorXd std;
};
ObservationScaling observation_scaling(const OfflineDataset& dataset, const std::vector<std::size_t>& rows);

// What COptiDICE takes from the training rows besides the scaling: the share of episodes' first rows
// among them (OSRL's init_state_propotion) and each action dimension's standard deviation.
struct TrainingStatistics {
  double initial_state_proportion = 1.0;
  Eigen::VectorXd action_std;  // empty: not known (a loaded checkpoint brings its own)
};
// `first_rows[t]` is 1 where row t begins an episode.
TrainingStatistics training_statistics(const OfflineDataset& dataset, const std::vector<std::size_t>& rows,
                                       const std::vector<char>& first_rows);
// 1 for each episode's first row of the dataset, 0 elsewhere.
std::vector<char> episode_first_rows(const OfflineDataset& dataset);

class OfflineBatches {
 public:
  // `dataset` must outlive this object.
  OfflineBatches(const OfflineDataset& dataset, TrainingRows rows, int batch_size);

  const TrainingRows& rows() const { return rows_; }
  const ObservationScaling& scaling() const { return scaling_; }
  const TrainingStatistics& statistics() const { return statistics_; }
  // Fills `batch` with batch_size rows, each uniform_index(rng, rows) in turn (every field; the next
  // observations standardised with the observations' constants; `initial` 1 for episodes' first rows).
  void sample(Rng& rng, OfflineBatch& batch) const;

 private:
  const OfflineDataset& dataset_;
  TrainingRows rows_;
  ObservationScaling scaling_;
  std::vector<char> first_rows_;
  TrainingStatistics statistics_;
  int batch_size_;
};

}  // namespace bsg::algos
