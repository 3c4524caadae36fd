// Online mean/std (docs/algorithms.md#observation-normaliser) against pooled statistics and the oracles of docs/algorithms.md#test-oracles.
#include "common/running_mean_std.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "common/random.h"

namespace bsg {
namespace {

// The data of the original's merged-statistics test (docs/algorithms.md#test-oracles): rank p, epoch e -> 0.001 * (start + arange(3000)) as 500 x 6, row-major.
Eigen::MatrixXd oracle_batch(int rank, int epoch) {
  Eigen::MatrixXd batch(500, 6);
  const double start = 10000.0 * rank + 4.0 * epoch;
  for (int i = 0; i < 500; ++i)
    for (int j = 0; j < 6; ++j) batch(i, j) = 0.001 * (start + 6 * i + j);
  return batch;
}

// Pooled (population) mean and std of the rows of several batches, in long double.
void pooled_statistics(const std::vector<Eigen::MatrixXd>& batches, Eigen::VectorXd& mean, Eigen::VectorXd& std) {
  const Eigen::Index d = batches.front().cols();
  mean.resize(d);
  std.resize(d);
  for (Eigen::Index j = 0; j < d; ++j) {
    long double sum = 0, count = 0;
    for (const auto& b : batches) {
      for (Eigen::Index i = 0; i < b.rows(); ++i) sum += b(i, j);
      count += b.rows();
    }
    const long double m = sum / count;
    long double squares = 0;
    for (const auto& b : batches)
      for (Eigen::Index i = 0; i < b.rows(); ++i) squares += (b(i, j) - m) * (b(i, j) - m);
    mean[j] = static_cast<double>(m);
    std[j] = static_cast<double>(std::sqrt(squares / count));
  }
}

TEST(RunningMeanStd, StartsAtZeroMeanUnitStd) {
  const RunningMeanStd stats(3);
  EXPECT_EQ(stats.mean(), Eigen::VectorXd::Zero(3));
  EXPECT_EQ(stats.std(), Eigen::VectorXd::Ones(3));
  EXPECT_EQ(stats.count(), 0.0);
  Eigen::VectorXd out(3);
  stats.normalize(Eigen::Vector3d(1.0, -2.0, 0.5), out);
  EXPECT_DOUBLE_EQ(out[1], -2.0 / (1.0 + 1e-5));  // epoch 0: x / (1 + 1e-5)
}

TEST(RunningMeanStd, TwentyStandardNormalBatchesMatchPooledStatistics) {
  // docs/algorithms.md#test-oracles.
  Rng rng(0);
  RunningMeanStd stats(1);
  std::vector<Eigen::MatrixXd> batches;
  for (int update = 0; update < 20; ++update) {
    Eigen::MatrixXd batch(500, 1);
    for (Eigen::Index i = 0; i < 500; ++i) batch(i, 0) = standard_normal(rng);
    stats.update(batch, MpiContext::single_process());
    batches.push_back(batch);
  }
  Eigen::VectorXd mean, std;
  pooled_statistics(batches, mean, std);
  EXPECT_NEAR(stats.mean()[0], mean[0], 1e-8 + 1e-5 * std::abs(mean[0]));
  EXPECT_NEAR(stats.std()[0], std[0], 1e-2 * std[0]);
  EXPECT_EQ(stats.count(), 10000.0);
}

TEST(RunningMeanStd, SingleRankMatrixOracleTellsQ4FromExactFormula) {
  // docs/algorithms.md#test-oracles (single rank, 20 epochs): Q4 std 0.866616, exact 0.866331.
  RunningMeanStd faithful(6);
  RunningMeanStd exact(6, RunningMeanStdOptions{.exact_parallel_variance = true});
  std::vector<Eigen::MatrixXd> batches;
  for (int epoch = 0; epoch < 20; ++epoch) {
    batches.push_back(oracle_batch(0, epoch));
    faithful.update(batches.back(), MpiContext::single_process());
    exact.update(batches.back(), MpiContext::single_process());
  }
  Eigen::VectorXd mean, std;
  pooled_statistics(batches, mean, std);
  EXPECT_NEAR(std[0], 0.866331, 5e-7);
  EXPECT_NEAR(faithful.std()[0], 0.866616, 5e-7);
  EXPECT_NEAR(exact.std()[0], std[0], 1e-12);
  for (int j = 0; j < 6; ++j) {
    EXPECT_NEAR(faithful.mean()[j], mean[j], 1e-12);
    EXPECT_NEAR(exact.mean()[j], mean[j], 1e-12);
  }
}

TEST(RunningMeanStd, FirstUpdateOfQ4AndExactFormulaAgree) {
  Rng rng(3);
  Eigen::MatrixXd batch(50, 2);
  for (Eigen::Index i = 0; i < batch.size(); ++i) batch.data()[i] = uniform(rng, -3.0, 5.0);
  RunningMeanStd faithful(2);
  RunningMeanStd exact(2, RunningMeanStdOptions{.exact_parallel_variance = true});
  faithful.update(batch, MpiContext::single_process());
  exact.update(batch, MpiContext::single_process());
  EXPECT_LT((faithful.std() - exact.std()).norm(), 1e-14);
  Eigen::VectorXd mean, std;
  pooled_statistics({batch}, mean, std);
  EXPECT_LT((faithful.std() - std).norm(), 1e-13);
  EXPECT_LT((faithful.mean() - mean).norm(), 1e-13);
}

TEST(RunningMeanStd, NormalizeUsesMeanAndStdPlusEpsilonAndOptionalClip) {
  RunningMeanStd stats(2);
  stats.set_state(Eigen::Vector2d(1.0, -1.0), Eigen::Vector2d(2.0, 0.5), 10.0);
  Eigen::VectorXd out(2);
  stats.normalize(Eigen::Vector2d(5.0, 10.0), out);
  EXPECT_DOUBLE_EQ(out[0], 4.0 / (2.0 + 1e-5));
  EXPECT_DOUBLE_EQ(out[1], 11.0 / (0.5 + 1e-5));  // no clipping by default (Q3)
  RunningMeanStd clipped(2, RunningMeanStdOptions{.clip = 10.0});
  clipped.set_state(stats.mean(), stats.std(), stats.count());
  clipped.normalize(Eigen::Vector2d(5.0, 10.0), out);
  EXPECT_DOUBLE_EQ(out[1], 10.0);
  Eigen::MatrixXd batch(2, 2), normalized(2, 2);
  batch << 5.0, 10.0, 1.0, -1.0;
  stats.normalize_batch(batch, normalized);
  EXPECT_DOUBLE_EQ(normalized(0, 0), 4.0 / (2.0 + 1e-5));
  EXPECT_DOUBLE_EQ(normalized(1, 1), 0.0);
}

TEST(RunningMeanStd, WrongSizesGiveExceptionsNamingTheInput) {
  EXPECT_THROW(RunningMeanStd(0), std::invalid_argument);
  RunningMeanStd stats(3);
  try {
    stats.update(Eigen::MatrixXd::Zero(4, 2), MpiContext::single_process());
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("batch has 2 columns"), std::string::npos) << e.what();
  }
  Eigen::VectorXd out(3);
  EXPECT_THROW(stats.normalize(Eigen::VectorXd::Zero(2), out), std::invalid_argument);
  Eigen::MatrixXd normalized(4, 3);
  EXPECT_THROW(stats.normalize_batch(Eigen::MatrixXd::Zero(5, 3), normalized), std::invalid_argument);
  EXPECT_THROW(stats.set_state(Eigen::VectorXd::Zero(3), Eigen::VectorXd::Ones(2), 1.0), std::invalid_argument);
  EXPECT_THROW(stats.set_state(Eigen::VectorXd::Zero(3), Eigen::VectorXd::Ones(3), -1.0), std::invalid_argument);
}

}  // namespace
}  // namespace bsg
