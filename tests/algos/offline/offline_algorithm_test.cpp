// The offline algorithm interface (algos/offline/offline_algorithm.h) as BehaviourCloning implements
// it, against hand-computed oracles: the loss of a batch is the mean squared error over every
// element; Adam's first step moves every parameter by -lr sign(dL/dtheta), the gradient of the
// linear policy's loss written out by hand; the training rows of BC-All and BC-Safe on a dataset of
// three episodes with known cost returns, and the standardisation of those rows; the state saved
// and loaded acts identically; and the factory builds both from a run config.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "algos/offline/behaviour_cloning.h"
#include "algos/offline/make_offline_algorithm.h"
#include "algos/offline/offline_batches.h"
#include "common/binary_io.h"
#include "common/random.h"

namespace bsg::algos {
namespace {

// Three episodes with 2-feature observations: lengths 2, 3, 1 and per-step costs 0, 1, 5.
OfflineDataset three_episodes() {
  OfflineDataset d;
  d.observation_dim = 2;
  d.action_dim = 1;
  const int lengths[] = {2, 3, 1};
  const float costs[] = {0.0f, 1.0f, 5.0f};
  float x = 0.0f;
  for (int e = 0; e < 3; ++e) {
    for (int t = 0; t < lengths[e]; ++t) {
      d.observations.insert(d.observations.end(), {x, 2.0f * x});
      d.next_observations.insert(d.next_observations.end(), {0.0f, 0.0f});
      d.actions.push_back(x / 10.0f);
      d.rewards.push_back(1.0f);
      d.costs.push_back(costs[e]);
      d.terminals.push_back(0.0f);
      d.timeouts.push_back(t + 1 == lengths[e] ? 1.0f : 0.0f);
      x += 1.0f;
    }
  }
  return d;
}

TEST(OfflineBatches, TrainingRowsOfBcAllAndBcSafe) {
  const OfflineDataset d = three_episodes();  // cost returns 0, 3, 5
  const TrainingRows all = all_rows(d);
  EXPECT_EQ(all.rows, (std::vector<std::size_t>{0, 1, 2, 3, 4, 5}));
  EXPECT_EQ(all.episodes, 3u);
  const TrainingRows within3 = rows_within_cost_limit(d, 3.0);
  EXPECT_EQ(within3.rows, (std::vector<std::size_t>{0, 1, 2, 3, 4}));
  EXPECT_EQ(within3.episodes, 2u);
  const TrainingRows within0 = rows_within_cost_limit(d, 0.0);
  EXPECT_EQ(within0.rows, (std::vector<std::size_t>{0, 1}));
  EXPECT_THROW(rows_within_cost_limit(d, -1.0), std::invalid_argument);
}

TEST(OfflineBatches, StandardisesWithTheTrainingRowsMoments) {
  const OfflineDataset d = three_episodes();
  // Rows 0, 1: x = 0, 1 -> mean 0.5, std 0.5 (population); the second feature 2x -> 1, 1.
  const ObservationScaling s = observation_scaling(d, {0, 1});
  EXPECT_DOUBLE_EQ(s.mean[0], 0.5);
  EXPECT_DOUBLE_EQ(s.std[0], 0.5);
  EXPECT_DOUBLE_EQ(s.mean[1], 1.0);
  EXPECT_DOUBLE_EQ(s.std[1], 1.0);
  // A constant feature keeps the scale 1.
  EXPECT_DOUBLE_EQ(observation_scaling(d, {3}).std[0], 1.0);

  OfflineBatches batches(d, rows_within_cost_limit(d, 0.0), 50);
  Rng rng(4);
  OfflineBatch batch;
  batches.sample(rng, batch);
  ASSERT_EQ(batch.observations.rows(), 50);
  for (Eigen::Index i = 0; i < 50; ++i) {
    // Row 0 standardises to (-1, -1) with action 0, row 1 to (1, 1) with action 0.1.
    const bool first = batch.observations(i, 0) < 0.0;
    EXPECT_DOUBLE_EQ(batch.observations(i, 0), first ? -1.0 : 1.0);
    EXPECT_DOUBLE_EQ(batch.observations(i, 1), first ? -1.0 : 1.0);
    EXPECT_NEAR(batch.actions(i, 0), first ? 0.0 : 0.1, 1e-7);
  }
}

TEST(BehaviourCloningAlgorithm, LossAndFirstAdamStepMatchTheHandGradient) {
  // A linear policy a = W s + b on 2 features and 2 actions.
  Rng init(7);
  const ObservationScaling unit{Eigen::VectorXd::Zero(2), Eigen::VectorXd::Ones(2)};
  const double lr = 0.01;
  BehaviourCloning bc("BC-All", 2, 2, unit, {}, MlpOptions{}, lr, init);
  const Eigen::VectorXd before = bc.network().parameters();
  // The parameters as W (2 x 2) and b: read them off the network's own outputs (a = W s + b).
  const auto output = [&](const Eigen::Vector2d& s) { return bc.network().forward(s); };
  const Eigen::Vector2d b = output(Eigen::Vector2d::Zero());
  Eigen::Matrix2d w;
  w.col(0) = output(Eigen::Vector2d(1, 0)) - b;
  w.col(1) = output(Eigen::Vector2d(0, 1)) - b;

  OfflineBatch batch;
  batch.observations.resize(3, 2);
  batch.observations << 1.0, 2.0, -0.5, 0.25, 0.0, -1.0;
  batch.actions.resize(3, 2);
  batch.actions << 0.3, -0.2, 1.0, 0.5, -0.7, 0.1;
  // L = sum over i, j of (W s_i + b - a_i)_j^2 / 6; dL/dW = 2/6 sum_i e_i s_i^T, dL/db = 2/6 sum_i e_i.
  double loss = 0.0;
  Eigen::Matrix2d grad_w = Eigen::Matrix2d::Zero();
  Eigen::Vector2d grad_b = Eigen::Vector2d::Zero();
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector2d s = batch.observations.row(i).transpose();
    const Eigen::Vector2d e = w * s + b - batch.actions.row(i).transpose();
    loss += e.squaredNorm() / 6.0;
    grad_w += (2.0 / 6.0) * e * s.transpose();
    grad_b += (2.0 / 6.0) * e;
  }
  Rng no_draws(0);
  EXPECT_NEAR(bc.update(batch, no_draws), loss, 1e-12);

  // Adam's first step: m = (1 - b1) g, v = (1 - b2) g^2, bias-corrected to g and g^2, so every
  // parameter moves by -lr g / (|g| + eps): -lr sign(g) for gradients far above eps.
  const Eigen::Vector2d b_after = bc.network().forward(Eigen::Vector2d::Zero());
  Eigen::Matrix2d w_after;
  w_after.col(0) = bc.network().forward(Eigen::Vector2d(1, 0)) - b_after;
  w_after.col(1) = bc.network().forward(Eigen::Vector2d(0, 1)) - b_after;
  for (int j = 0; j < 2; ++j) {
    EXPECT_NEAR(b_after[j] - b[j], -lr * grad_b[j] / (std::abs(grad_b[j]) + 1e-8), 1e-9);
    for (int k = 0; k < 2; ++k) {
      EXPECT_NEAR(w_after(j, k) - w(j, k), -lr * grad_w(j, k) / (std::abs(grad_w(j, k)) + 1e-8), 1e-9);
    }
  }
  EXPECT_NE(bc.network().parameters(), before);
}

TEST(BehaviourCloningAlgorithm, ActsOnRawObservationsThroughItsStandardisation) {
  Rng init(3);
  const ObservationScaling scaling{Eigen::Vector2d(1.0, -2.0), Eigen::Vector2d(2.0, 4.0)};
  BehaviourCloning bc("BC-Safe", 2, 1, scaling, {8}, MlpOptions{}, 1e-3, init);
  const std::vector<double> raw{3.0, 2.0};
  std::vector<double> action(1);
  Rng unused(0);
  bc.acting().act(raw, ActionMode::sampled, unused, action);
  // (3 - 1) / 2 = 1, (2 + 2) / 4 = 1.
  EXPECT_DOUBLE_EQ(action[0], bc.network().forward(Eigen::Vector2d(1.0, 1.0))[0]);
  std::vector<double> wrong(3);
  EXPECT_THROW(bc.acting().act(wrong, ActionMode::mean, unused, action), std::invalid_argument);
}

TEST(BehaviourCloningAlgorithm, SavedStateLoadsIntoAFreshOneAndActsAlike) {
  const OfflineDataset d = three_episodes();
  OfflineBatches batches(d, all_rows(d), 4);
  Rng init(1), sample(2);
  BehaviourCloning trained("BC-All", 2, 1, batches.scaling(), {5, 5}, MlpOptions{}, 1e-2, init);
  OfflineBatch batch;
  for (int u = 0; u < 10; ++u) {
    batches.sample(sample, batch);
    trained.update(batch, sample);
  }
  BinaryWriter writer;
  trained.save(writer);

  Rng other(99);
  const ObservationScaling placeholder{Eigen::VectorXd::Zero(2), Eigen::VectorXd::Ones(2)};
  BehaviourCloning loaded("BC-All", 2, 1, placeholder, {5, 5}, MlpOptions{}, 1e-2, other);
  BinaryReader reader(writer.bytes(), "test");
  loaded.load(reader);
  reader.expect_end();
  EXPECT_EQ(loaded.network().parameters(), trained.network().parameters());
  EXPECT_EQ(loaded.scaling().mean, trained.scaling().mean);
  // The optimiser state came along: one more step on the same batch agrees too.
  EXPECT_EQ(loaded.update(batch, sample), trained.update(batch, sample));
  EXPECT_EQ(loaded.network().parameters(), trained.network().parameters());

  BehaviourCloning safe("BC-Safe", 2, 1, placeholder, {5, 5}, MlpOptions{}, 1e-2, other);
  BinaryReader again(writer.bytes(), "test");
  EXPECT_THROW(safe.load(again), CheckpointError);
}

TEST(MakeOfflineAlgorithm, BuildsBothFromTheConfig) {
  const OfflineDataset d = three_episodes();
  RunConfig config;
  config.hidden_sizes = {4};
  config.cost_limit = 3.0;
  const ObservationScaling unit{Eigen::VectorXd::Zero(2), Eigen::VectorXd::Ones(2)};
  Rng init(0);
  config.alg = Algorithm::bc_all;
  EXPECT_EQ(make_offline_algorithm(config, 2, 1, unit, init)->name(), "BC-All");
  EXPECT_EQ(offline_training_rows(config, d).rows.size(), 6u);
  config.alg = Algorithm::bc_safe;
  EXPECT_EQ(make_offline_algorithm(config, 2, 1, unit, init)->name(), "BC-Safe");
  EXPECT_EQ(offline_training_rows(config, d).rows.size(), 5u);
  config.alg = Algorithm::sac;
  EXPECT_THROW(make_offline_algorithm(config, 2, 1, unit, init), std::invalid_argument);
}

}  // namespace
}  // namespace bsg::algos
