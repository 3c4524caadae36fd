#include "algos/core/epoch_statistics.h"

#include <cmath>
#include <limits>

namespace bsg::algos {

PooledStatistics pool_statistics(const Eigen::Ref<const Eigen::VectorXd>& local_values, const MpiContext& mpi) {
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  double sum_and_count[2] = {local_values.sum(), static_cast<double>(local_values.size())};
  mpi.sum_in_place(sum_and_count, 2);
  PooledStatistics stats;
  stats.count = static_cast<long long>(sum_and_count[1]);
  const double mean = stats.count > 0 ? sum_and_count[0] / sum_and_count[1] : std::nan("");
  const double local_squared_deviations = stats.count > 0 ? (local_values.array() - mean).square().sum() : 0.0;
  const double squared_deviations = mpi.sum(local_squared_deviations);
  const double min = mpi.min(local_values.size() > 0 ? local_values.minCoeff() : kInfinity);
  const double max = mpi.max(local_values.size() > 0 ? local_values.maxCoeff() : -kInfinity);
  if (stats.count == 0) {
    stats.mean = stats.std = stats.min = stats.max = std::nan("");
    return stats;
  }
  stats.mean = mean;
  stats.std = std::sqrt(squared_deviations / sum_and_count[1]);
  stats.min = min;
  stats.max = max;
  return stats;
}

}  // namespace bsg::algos
