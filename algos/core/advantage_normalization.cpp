#include "algos/core/advantage_normalization.h"

#include "algos/core/epoch_statistics.h"

namespace bsg::algos {
namespace {

void center_cost_advantages(Eigen::MatrixXd& costs, const MpiContext& mpi) {
  for (Eigen::Index i = 0; i < costs.cols(); ++i) {
    const PooledStatistics cost = pool_statistics(costs.col(i), mpi);
    costs.col(i).array() -= cost.mean;
  }
}

}  // namespace

void standardize_advantages(Eigen::VectorXd& reward, Eigen::MatrixXd& costs, const MpiContext& mpi) {
  const PooledStatistics pooled = pool_statistics(reward, mpi);
  reward = (reward.array() - pooled.mean) / (pooled.std + 1e-8);
  center_cost_advantages(costs, mpi);
}

void center_advantages(Eigen::VectorXd& reward, Eigen::MatrixXd& costs, const MpiContext& mpi) {
  // An over- or under-predicting V adds a multiple of the short-term reward-to-go to every advantage
  // (docs/algorithms.md#reward-scaling-and-unlearning); centring removes its batch mean.
  const PooledStatistics pooled = pool_statistics(reward, mpi);
  reward.array() -= pooled.mean;
  center_cost_advantages(costs, mpi);
}

}  // namespace bsg::algos
