#include "algos/offline/offline_batches.h"

#include <stdexcept>
#include <string>

namespace bsg::algos {
namespace {

Eigen::VectorXd observation_of(const OfflineDataset& dataset, std::size_t row,
                               const std::vector<float> OfflineDataset::*array = &OfflineDataset::observations) {
  const int obs = dataset.observation_dim;
  return Eigen::Map<const Eigen::VectorXf>((dataset.*array).data() + row * static_cast<std::size_t>(obs), obs)
      .cast<double>();
}

}  // namespace

TrainingRows all_rows(const OfflineDataset& dataset) {
  check_dataset_shapes(dataset);
  TrainingRows result;
  result.episodes = dataset_episodes(dataset).size();
  for (std::size_t t = 0; t < dataset.size(); ++t) result.rows.push_back(t);
  if (result.rows.empty()) throw std::invalid_argument("behaviour cloning: the dataset is empty");
  return result;
}

TrainingRows rows_within_cost_limit(const OfflineDataset& dataset, double cost_limit) {
  check_dataset_shapes(dataset);
  TrainingRows result;
  for (const DatasetEpisode& e : dataset_episodes(dataset)) {
    if (e.cost_return > cost_limit) continue;
    ++result.episodes;
    for (std::size_t t = e.begin; t < e.end; ++t) result.rows.push_back(t);
  }
  if (result.rows.empty()) {
    throw std::invalid_argument("behaviour cloning: BC-Safe finds no episode with cost return <= " +
                                std::to_string(cost_limit) + " in the dataset");
  }
  return result;
}

ObservationScaling observation_scaling(const OfflineDataset& dataset, const std::vector<std::size_t>& rows) {
  const int obs = dataset.observation_dim;
  ObservationScaling scaling;
  scaling.mean = Eigen::VectorXd::Zero(obs);
  for (std::size_t row : rows) scaling.mean += observation_of(dataset, row);
  scaling.mean /= static_cast<double>(rows.size());
  Eigen::VectorXd variance = Eigen::VectorXd::Zero(obs);
  for (std::size_t row : rows) variance += (observation_of(dataset, row) - scaling.mean).array().square().matrix();
  variance /= static_cast<double>(rows.size());
  scaling.std = variance.cwiseSqrt();
  for (Eigen::Index k = 0; k < obs; ++k) {
    if (!(scaling.std[k] > 1e-8)) scaling.std[k] = 1.0;
  }
  return scaling;
}

std::vector<char> episode_first_rows(const OfflineDataset& dataset) {
  std::vector<char> first(dataset.size(), 0);
  for (const DatasetEpisode& e : dataset_episodes(dataset)) {
    if (e.begin < first.size()) first[e.begin] = 1;
  }
  return first;
}

TrainingStatistics training_statistics(const OfflineDataset& dataset, const std::vector<std::size_t>& rows,
                                       const std::vector<char>& first_rows) {
  const int act = dataset.action_dim;
  TrainingStatistics statistics;
  std::size_t initial = 0;
  Eigen::VectorXd mean = Eigen::VectorXd::Zero(act);
  for (std::size_t row : rows) {
    initial += first_rows[row] != 0 ? 1 : 0;
    for (int j = 0; j < act; ++j) mean[j] += dataset.actions[row * static_cast<std::size_t>(act) + j];
  }
  mean /= static_cast<double>(rows.size());
  Eigen::VectorXd variance = Eigen::VectorXd::Zero(act);
  for (std::size_t row : rows) {
    for (int j = 0; j < act; ++j) {
      const double d = dataset.actions[row * static_cast<std::size_t>(act) + j] - mean[j];
      variance[j] += d * d;
    }
  }
  statistics.action_std = (variance / static_cast<double>(rows.size())).cwiseSqrt();  // numpy's std (ddof 0)
  statistics.initial_state_proportion = static_cast<double>(initial) / static_cast<double>(rows.size());
  return statistics;
}

OfflineBatches::OfflineBatches(const OfflineDataset& dataset, TrainingRows rows, int batch_size)
    : dataset_(dataset), rows_(std::move(rows)), batch_size_(batch_size) {
  if (batch_size < 1) throw std::invalid_argument("offline batches: the batch size must be >= 1");
  if (rows_.rows.empty()) throw std::invalid_argument("offline batches: no training rows");
  scaling_ = observation_scaling(dataset_, rows_.rows);
  first_rows_ = episode_first_rows(dataset_);
  statistics_ = training_statistics(dataset_, rows_.rows, first_rows_);
}

void OfflineBatches::sample(Rng& rng, OfflineBatch& batch) const {
  const int obs = dataset_.observation_dim;
  const int act = dataset_.action_dim;
  batch.observations.resize(batch_size_, obs);
  batch.actions.resize(batch_size_, act);
  batch.next_observations.resize(batch_size_, obs);
  batch.rewards.resize(batch_size_);
  batch.costs.resize(batch_size_);
  batch.terminals.resize(batch_size_);
  batch.initial.resize(batch_size_);
  for (Eigen::Index i = 0; i < batch_size_; ++i) {
    const std::size_t row = rows_.rows[uniform_index(rng, rows_.rows.size())];
    batch.observations.row(i) = (observation_of(dataset_, row) - scaling_.mean).cwiseQuotient(scaling_.std).transpose();
    batch.actions.row(i) =
        Eigen::Map<const Eigen::VectorXf>(dataset_.actions.data() + row * static_cast<std::size_t>(act), act)
            .cast<double>()
            .transpose();
    batch.next_observations.row(i) =
        (observation_of(dataset_, row, &OfflineDataset::next_observations) - scaling_.mean)
            .cwiseQuotient(scaling_.std)
            .transpose();
    batch.rewards(i) = dataset_.rewards[row];
    batch.costs(i) = dataset_.costs[row];
    batch.terminals(i) = dataset_.terminals[row];
    batch.initial(i) = first_rows_[row];
  }
}

}  // namespace bsg::algos
