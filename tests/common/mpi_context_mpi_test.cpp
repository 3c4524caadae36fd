// The MPI wrapper and the merged running statistics under `mpirun -np 2`.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "common/mpi_context.h"
#include "common/random.h"
#include "common/running_mean_std.h"

namespace bsg {
namespace {

// Rank r's deterministic data: different row counts per rank are allowed.
Eigen::MatrixXd rank_batch(int rank, int epoch, Eigen::Index rows) {
  Rng rng(1000 * rank + epoch);
  Eigen::MatrixXd batch(rows, 3);
  for (Eigen::Index i = 0; i < batch.size(); ++i) batch.data()[i] = 5.0 * rank + standard_normal(rng) * (1 + rank);
  return batch;
}

TEST(MpiContextMpi, RankAndSize) {
  const MpiContext mpi = MpiContext::world();
  ASSERT_EQ(mpi.size(), 2);
  EXPECT_EQ(mpi.is_root(), mpi.rank() == 0);
}

TEST(MpiContextMpi, AverageSumMinMaxOfVectorsAndScalars) {
  const MpiContext mpi = MpiContext::world();
  const double r = mpi.rank();
  Eigen::VectorXd values(3);
  values << r, 10.0 * r, -1.0;
  mpi.average_in_place(values);
  EXPECT_DOUBLE_EQ(values[0], 0.5);
  EXPECT_DOUBLE_EQ(values[1], 5.0);
  EXPECT_DOUBLE_EQ(values[2], -1.0);
  Eigen::VectorXd sums = Eigen::VectorXd::Constant(2, r + 1.0);
  mpi.sum_in_place(sums);
  EXPECT_DOUBLE_EQ(sums[0], 3.0);
  EXPECT_DOUBLE_EQ(mpi.average(r), 0.5);
  EXPECT_DOUBLE_EQ(mpi.sum(r + 1.0), 3.0);
  EXPECT_EQ(mpi.sum(static_cast<long long>(r) + 1), 3LL);
  EXPECT_DOUBLE_EQ(mpi.min(r), 0.0);
  EXPECT_DOUBLE_EQ(mpi.max(r), 1.0);
}

TEST(MpiContextMpi, BroadcastMakesParametersIdenticalOnAllRanks) {
  const MpiContext mpi = MpiContext::world();
  Rng rng(77 + mpi.rank());  // different data on every rank
  Eigen::VectorXd parameters(1000);
  for (Eigen::Index i = 0; i < parameters.size(); ++i) parameters[i] = standard_normal(rng);
  Rng root_rng(77);
  Eigen::VectorXd root_parameters(1000);
  for (Eigen::Index i = 0; i < root_parameters.size(); ++i) root_parameters[i] = standard_normal(root_rng);
  mpi.broadcast_from_root(parameters);
  EXPECT_EQ(parameters, root_parameters);
  EXPECT_EQ(mpi.min(parameters.sum()), mpi.max(parameters.sum()));
}

TEST(MpiContextMpi, GatherToRootConcatenatesInRankOrder) {
  const MpiContext mpi = MpiContext::world();
  std::vector<double> local(static_cast<std::size_t>(mpi.rank() + 1), static_cast<double>(mpi.rank()));
  const std::vector<double> gathered = mpi.gather_to_root(local);
  if (mpi.is_root()) {
    EXPECT_EQ(gathered, (std::vector<double>{0.0, 1.0, 1.0}));
  } else {
    EXPECT_TRUE(gathered.empty());
  }
}

TEST(MpiContextMpi, MergedStatisticsEqualThoseOfTheUnionOfBothRanks) {
  const MpiContext mpi = MpiContext::world();
  RunningMeanStd faithful(3);
  RunningMeanStd exact(3, RunningMeanStdOptions{.exact_parallel_variance = true});
  RunningMeanStd single_faithful(3);
  RunningMeanStd single_exact(3, RunningMeanStdOptions{.exact_parallel_variance = true});
  for (int epoch = 0; epoch < 5; ++epoch) {
    const Eigen::Index rows = 200;
    const Eigen::MatrixXd local = rank_batch(mpi.rank(), epoch, rows);
    faithful.update(local, mpi);
    exact.update(local, mpi);
    // Oracle: one process updating with the union of both ranks' rows.
    Eigen::MatrixXd both(2 * rows, 3);
    both << rank_batch(0, epoch, rows), rank_batch(1, epoch, rows);
    single_faithful.update(both, MpiContext::single_process());
    single_exact.update(both, MpiContext::single_process());
  }
  EXPECT_EQ(faithful.count(), 2000.0);
  EXPECT_LT((faithful.mean() - single_faithful.mean()).norm(), 1e-12);
  EXPECT_LT((faithful.std() - single_faithful.std()).norm(), 1e-12);
  EXPECT_LT((exact.mean() - single_exact.mean()).norm(), 1e-12);
  EXPECT_LT((exact.std() - single_exact.std()).norm(), 1e-12);
}

TEST(MpiContextMpi, SpecOracleDataWithTwoRanksMatchesPooledStatistics) {
  // docs/algorithms.md#test-oracles with 2 ranks instead of 4: pooled mean exact, Q4 std within rtol 1e-5.
  const MpiContext mpi = MpiContext::world();
  RunningMeanStd stats(6);
  long double sum = 0, squares = 0, count = 0;
  for (int epoch = 0; epoch < 20; ++epoch) {
    Eigen::MatrixXd batch(500, 6);
    for (int i = 0; i < 500; ++i)
      for (int j = 0; j < 6; ++j) batch(i, j) = 0.001 * (10000.0 * mpi.rank() + 4.0 * epoch + 6 * i + j);
    stats.update(batch, mpi);
    for (int rank = 0; rank < 2; ++rank)
      for (int i = 0; i < 500; ++i) {
        const long double x = 0.001L * (10000.0L * rank + 4.0L * epoch + 6 * i);  // column 0
        sum += x;
        squares += x * x;
        count += 1;
      }
  }
  const long double mean = sum / count;
  const double pooled_std = static_cast<double>(std::sqrt(squares / count - mean * mean));
  EXPECT_NEAR(stats.mean()[0], static_cast<double>(mean), 1e-9);
  EXPECT_NEAR(stats.mean()[5], static_cast<double>(mean) + 0.005, 1e-9);
  EXPECT_NEAR(stats.std()[0], pooled_std, 1e-5 * pooled_std);
}

TEST(MpiContextMpi, BroadcastOfRunningStatisticsCopiesRankZero) {
  const MpiContext mpi = MpiContext::world();
  RunningMeanStd stats(2);
  stats.set_state(Eigen::Vector2d::Constant(mpi.rank()), Eigen::Vector2d::Constant(1.0 + mpi.rank()),
                  10.0 * (mpi.rank() + 1));
  stats.broadcast_from_root(mpi);
  EXPECT_EQ(stats.mean(), Eigen::Vector2d::Zero());
  EXPECT_EQ(stats.std(), Eigen::Vector2d::Ones());
  EXPECT_EQ(stats.count(), 10.0);
}

}  // namespace
}  // namespace bsg
