// Statistics pooled over MPI ranks (docs/algorithms.md#across-mpi-ranks): every rank contributes its local
// values (e.g. the returns of the episodes it completed), and every rank gets
// the global mean = sum of values / sum of counts, the population standard
// deviation about that mean, and the global minimum and maximum. With no value
// on any rank every field is NaN and count is 0. Collective.
#pragma once

#include <Eigen/Core>

#include "common/mpi_context.h"

namespace bsg::algos {

struct PooledStatistics {
  double mean = 0.0;
  double std = 0.0;
  double min = 0.0;
  double max = 0.0;
  long long count = 0;
};

PooledStatistics pool_statistics(const Eigen::Ref<const Eigen::VectorXd>& local_values, const MpiContext& mpi);

}  // namespace bsg::algos
