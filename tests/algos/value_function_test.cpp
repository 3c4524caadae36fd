// Value-function fitting with the schedule of docs/algorithms.md#value-fits and the invariants of docs/algorithms.md#test-oracles.
#include "algos/value_function.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "../common/finite_differences.h"

namespace bsg {
namespace {

Eigen::MatrixXd random_observations(Eigen::Index n, int d, Rng& rng) {
  Eigen::MatrixXd m(n, d);
  for (Eigen::Index i = 0; i < m.size(); ++i) m.data()[i] = standard_normal(rng);
  return m;
}

TEST(ValueFunction, AdamStepCountIsFivePassesOfCeilNOverFloorNOverSixteen) {
  Rng rng(1);
  const MpiContext mpi = MpiContext::single_process();
  for (const auto& [n, steps] : {std::pair<Eigen::Index, int>{512, 80}, {500, 85}, {1000, 85}}) {
    ValueFunction value(3, {8, 8}, rng);
    const Eigen::MatrixXd obs = random_observations(n, 3, rng);
    const ValueFitStats stats = value.fit(obs, Eigen::VectorXd::Zero(n), rng, mpi);
    EXPECT_EQ(stats.adam_steps, steps) << "N = " << n;
    EXPECT_EQ(value.optimizer().step_count(), steps);
  }
}

TEST(ValueFunction, TargetsEqualToPredictionsLeaveAFreshNetUnchanged) {
  Rng rng(2);
  ValueFunction value(3, {16, 16}, rng);
  // A zero output layer (its 16 weights and bias are the last 17 parameters,
  // docs/algorithms.md#networks) predicts exactly 0 on every batch and minibatch, so with zero
  // targets the gradient is exactly zero. Targets merely *computed* from the
  // net would differ from the minibatch predictions by rounding (FMA kernels
  // depend on the batch size), and Adam turns any non-zero gradient into a
  // step of order lr.
  Eigen::VectorXd parameters = value.net().parameters();
  parameters.tail(17).setZero();
  value.net().set_parameters(parameters);
  const Eigen::MatrixXd obs = random_observations(320, 3, rng);
  const Eigen::VectorXd targets = Eigen::VectorXd::Zero(320);
  const ValueFitStats stats = value.fit(obs, targets, rng, MpiContext::single_process());
  EXPECT_EQ(stats.loss_before, 0.0);
  EXPECT_EQ(value.net().parameters(), parameters);
}

TEST(ValueFunction, PersistedAdamMomentumStillMovesTheNet) {
  Rng rng(3);
  ValueFunction value(3, {16, 16}, rng);
  const Eigen::MatrixXd obs = random_observations(320, 3, rng);
  value.fit(obs, Eigen::VectorXd::Constant(320, 5.0), rng, MpiContext::single_process());
  Eigen::VectorXd targets(320);
  value.predict_batch(obs, targets);
  const Eigen::VectorXd before = value.net().parameters();
  value.fit(obs, targets, rng, MpiContext::single_process());
  EXPECT_GT((value.net().parameters() - before).cwiseAbs().maxCoeff(), 1e-4);
}

TEST(ValueFunction, FittingReducesTheLossOnASmoothTarget) {
  Rng rng(4);
  ValueFunction value(2, {64, 64}, rng);
  const Eigen::MatrixXd obs = random_observations(1024, 2, rng);
  const Eigen::VectorXd targets = (obs.col(0).array().sin() + 0.5 * obs.col(1).array()).matrix();
  const double initial = value.loss(obs, targets);
  ValueFitStats stats;
  for (int epoch = 0; epoch < 10; ++epoch) stats = value.fit(obs, targets, rng, MpiContext::single_process());
  EXPECT_LT(value.loss(obs, targets), 0.2 * initial);
  EXPECT_LT(stats.mean_minibatch_loss, initial);
}

TEST(ValueFunction, LossBeforeIsTheFullBatchMeanSquaredError) {
  Rng rng(5);
  ValueFunction value(2, {4}, rng);
  const Eigen::MatrixXd obs = random_observations(256, 2, rng);
  const Eigen::VectorXd targets = Eigen::VectorXd::Constant(256, 0.7);
  double expected = 0.0;
  MlpSampleWorkspace workspace;
  for (Eigen::Index i = 0; i < 256; ++i) {
    const double v = value.predict(obs.row(i).transpose(), workspace);
    expected += (v - 0.7) * (v - 0.7) / 256.0;
  }
  const ValueFitStats stats = value.fit(obs, targets, rng, MpiContext::single_process());
  EXPECT_NEAR(stats.loss_before, expected, 1e-14);
}

TEST(ValueFunction, BadInputGivesExceptions) {
  Rng rng(6);
  ValueFunction value(2, {4}, rng);
  const MpiContext mpi = MpiContext::single_process();
  try {
    value.fit(Eigen::MatrixXd::Zero(200, 2), Eigen::VectorXd::Zero(200), rng, mpi);  // m = 12 < 16
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("min_mini_batch_size"), std::string::npos) << e.what();
  }
  EXPECT_NO_THROW(value.fit(Eigen::MatrixXd::Zero(200, 2), Eigen::VectorXd::Zero(200), rng, mpi,
                            ValueFitOptions{.min_mini_batch_size = 1}));
  EXPECT_THROW(value.fit(Eigen::MatrixXd::Zero(300, 2), Eigen::VectorXd::Zero(299), rng, mpi), std::invalid_argument);
  EXPECT_THROW(value.fit(Eigen::MatrixXd::Zero(300, 3), Eigen::VectorXd::Zero(300), rng, mpi), std::invalid_argument);
  Eigen::VectorXd values(3);
  EXPECT_THROW(value.predict_batch(Eigen::MatrixXd::Zero(4, 2), values), std::invalid_argument);
}

}  // namespace
}  // namespace bsg
