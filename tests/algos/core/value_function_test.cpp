// Value-function fitting with the schedule of docs/algorithms.md#value-fits and the invariants of docs/algorithms.md#test-oracles.
#include "algos/core/value_function.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "../../common/finite_differences.h"

namespace bsg::algos {
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
TEST(ValueFunction, FittingTwoNetsTogetherEqualsFittingEachOnTheSameShuffles) {
  // fit_value_functions shares each shuffle and minibatch between V and V_C;
  // the oracle fits each net alone with the shuffle RNG restarted from the
  // same seed, which draws the same permutations.
  Rng init(7);
  const MpiContext mpi = MpiContext::single_process();
  ValueFunction together_v(3, {16, 16}, init);
  ValueFunction together_c(3, {16, 16}, init);
  ValueFunction alone_v = together_v;
  ValueFunction alone_c = together_c;
  const Eigen::MatrixXd obs = random_observations(500, 3, init);
  const Eigen::VectorXd targets = random_observations(500, 1, init);
  const Eigen::VectorXd cost_targets = random_observations(500, 1, init).array().abs();

  Rng shuffle(11);
  const std::vector<ValueFitJob> jobs{{together_v, targets}, {together_c, cost_targets}};
  const std::vector<ValueFitStats> together = fit_value_functions(jobs, obs, shuffle, mpi);
  Rng shuffle_v(11), shuffle_c(11);
  const ValueFitStats stats_v = alone_v.fit(obs, targets, shuffle_v, mpi);
  const ValueFitStats stats_c = alone_c.fit(obs, cost_targets, shuffle_c, mpi);

  ASSERT_EQ(together.size(), 2u);
  EXPECT_EQ(together_v.net().parameters(), alone_v.net().parameters());
  EXPECT_EQ(together_c.net().parameters(), alone_c.net().parameters());
  EXPECT_EQ(together[0].adam_steps, stats_v.adam_steps);
  EXPECT_EQ(together[1].loss_before, stats_c.loss_before);
  EXPECT_EQ(together[1].mean_minibatch_loss, stats_c.mean_minibatch_loss);
  EXPECT_NE(together_v.net().parameters(), together_c.net().parameters());
}

TEST(ValueFunction, AFloat32FitFollowsTheFloat64FitClosely) {
  // The float64 fit is the oracle: 85 Adam steps of lr 1e-3 move each
  // parameter by up to ~0.085; single-precision gradients change the path by
  // far less than that.
  Rng init(8);
  ValueFunction value64(3, {16, 16}, init);
  ValueFunction value32(3, {16, 16}, init, MlpOptions{.zero_bias_init = false, .dtype = Dtype::float32});
  value32.net().set_parameters(value64.net().parameters());
  const Eigen::VectorXd start = value64.net().parameters();
  const Eigen::MatrixXd obs = random_observations(500, 3, init);
  const Eigen::VectorXd targets = (obs.col(0).array().sin() + obs.col(1).array()).matrix();
  Rng shuffle64(3), shuffle32(3);
  const ValueFitStats stats64 = value64.fit(obs, targets, shuffle64, MpiContext::single_process());
  const ValueFitStats stats32 = value32.fit(obs, targets, shuffle32, MpiContext::single_process());
  const double moved = (value64.net().parameters() - start).norm();
  EXPECT_GT(moved, 0.05);
  EXPECT_LT((value32.net().parameters() - value64.net().parameters()).norm(), 1e-3 * moved);
  EXPECT_NEAR(stats32.loss_before, stats64.loss_before, 1e-5 * stats64.loss_before);
  EXPECT_NEAR(stats32.mean_minibatch_loss, stats64.mean_minibatch_loss, 1e-4 * stats64.mean_minibatch_loss);
}

}  // namespace bsg::algos
