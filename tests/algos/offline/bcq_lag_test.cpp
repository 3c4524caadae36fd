// BCQ-Lag (algos/offline/bcq_lag.h) against independent oracles: OSRL's PID controller over a
// sequence worked out by hand; the perturbation's clamp on hand-picked proposals; the critics' targets
// computed row by row from the networks' single-sample passes (decoder, target actor, the four target
// critics of each kind, the lambda-weighted min and max of the heads, the best of the proposals); the
// losses written out sample by sample and their gradients against central differences; the acting
// policy at z = 0 through the standardisation; the saved state continuing as the original.
#include "algos/offline/bcq_lag.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "algos/offline/make_offline_algorithm.h"
#include "common/binary_io.h"
#include "offline_test_support.h"

namespace bsg::algos {
namespace {
namespace bcq_lag_test {

using testing::expect_central_differences;
using testing::normal_matrix;
using testing::q_of;

constexpr int kObs = 3;
constexpr int kAct = 2;
constexpr int kRows = 4;
constexpr int kNets = 2 * kBcqEnsemble;

BcqLagOptions small_options(double cost_limit) {
  BcqLagOptions options;
  testing::set_small_vae_learner_options(options, cost_limit);
  options.phi = 0.3;
  options.lambda_mix = 0.75;
  return options;
}

ObservationScaling unit_scaling() { return testing::unit_scaling(kObs); }

OfflineBatch random_batch(Rng& rng) { return testing::random_offline_batch(rng, kObs, kAct); }

// Moves every target network away from its online copy, so that the targets' use is seen.
void perturb_targets(BcqLag& bcq, Rng& rng) {
  std::vector<Mlp*> targets{&bcq.target_actor()};
  for (int k = 0; k < kNets; ++k) {
    targets.push_back(&bcq.target_reward_critic(k));
    targets.push_back(&bcq.target_cost_critic(k));
  }
  for (Mlp* target : targets) {
    Eigen::VectorXd p = target->parameters();
    for (Eigen::Index i = 0; i < p.size(); ++i) p[i] += 0.3 * standard_normal(rng);
    target->set_parameters(p);
  }
}

// One row's action: a_hat = tanh(decoder([s, z])), then clamp(a_hat + phi tanh(xi([s, a_hat])), -1, 1).
Eigen::VectorXd action_of(BcqLag& bcq, const Mlp& perturbation, const Eigen::VectorXd& s, const Eigen::VectorXd& z) {
  Eigen::VectorXd decoder_input(s.size() + z.size());
  decoder_input << s, z;
  const Eigen::VectorXd proposal = bcq.vae().decoder().forward(decoder_input).array().tanh();
  Eigen::VectorXd actor_input(s.size() + kAct);
  actor_input << s, proposal;
  const Eigen::VectorXd xi = perturbation.forward(actor_input);
  Eigen::VectorXd a(kAct);
  for (int j = 0; j < kAct; ++j) a[j] = std::clamp(proposal[j] + bcq.options().phi * std::tanh(xi[j]), -1.0, 1.0);
  return a;
}

TEST(BcqLag, PidControllerIsOsrls) {
  // K = (0.1, 0.003, 0.001); errors 2, 5, -1, -9:
  //   e=2:  D = 2, I = 2,  mu = 0.1*2 + 0.003*2 + 0.001*2 = 0.208
  //   e=5:  D = 3, I = 7,  mu = 0.5 + 0.021 + 0.003 = 0.524
  //   e=-1: D = 0, I = 6,  mu = 0 + 0.018 + 0 = 0.018
  //   e=-9: D = 0, I = 0,  mu = 0
  BcqPidController pid{.kp = 0.1, .ki = 0.003, .kd = 0.001};
  EXPECT_NEAR(pid.control(2.0), 0.208, 1e-15);
  EXPECT_NEAR(pid.control(5.0), 0.524, 1e-15);
  EXPECT_NEAR(pid.control(-1.0), 0.018, 1e-15);
  EXPECT_EQ(pid.control(-9.0), 0.0);
  EXPECT_EQ(pid.integral, 0.0);
  EXPECT_EQ(pid.previous_error, -9.0);
}

TEST(BcqLag, ThresholdIsOsrls) {
  BcqLagOptions options;  // d = 10, gamma = 0.99, T = 300
  EXPECT_NEAR(options.cost_threshold(), 3.16986, 1e-5);
}

TEST(BcqLag, PerturbationStaysWithinPhiAndTheActionBox) {
  Rng init(1);
  BcqLag bcq(kObs, kAct, unit_scaling(), small_options(5.0), init);
  Eigen::MatrixXd s(3, kObs);
  s << 0.1, -0.2, 0.3, 1.0, 0.5, -0.5, -1.0, 0.0, 2.0;
  Eigen::MatrixXd proposals(3, kAct);
  proposals << 0.0, 0.5, 0.95, -0.95, -0.99, 0.2;  // near the bounds: the clamp may bind
  MlpBatchWorkspace workspace;
  Eigen::MatrixXd actions;
  bcq.perturb(bcq.actor(), s, proposals, workspace, actions);
  for (int i = 0; i < 3; ++i) {
    Eigen::VectorXd input(kObs + kAct);
    input << s.row(i).transpose(), proposals.row(i).transpose();
    const Eigen::VectorXd xi = bcq.actor().forward(input);
    for (int j = 0; j < kAct; ++j) {
      double expected = proposals(i, j) + 0.3 * std::tanh(xi[j]);
      expected = expected > 1.0 ? 1.0 : expected < -1.0 ? -1.0 : expected;
      EXPECT_NEAR(actions(i, j), expected, 1e-15) << i << "," << j;
      EXPECT_LE(std::abs(actions(i, j) - proposals(i, j)), 0.3 + 1e-15);
    }
  }
}

TEST(BcqLag, TargetsRowByRow) {
  Rng init(2), rng(3);
  BcqLag bcq(kObs, kAct, unit_scaling(), small_options(5.0), init);
  perturb_targets(bcq, rng);
  const OfflineBatch batch = random_batch(rng);
  const int m = bcq.options().sampled_actions;
  const int latent = bcq.vae().latent_size();
  const Eigen::MatrixXd reward_latents = 0.5 * normal_matrix(kRows * m, latent, rng);
  const Eigen::MatrixXd cost_latents = 0.5 * normal_matrix(kRows * m, latent, rng);
  bcq.compute_targets(batch, reward_latents, cost_latents);
  const BcqLagOptions& o = bcq.options();
  for (int i = 0; i < kRows; ++i) {
    const Eigen::VectorXd s = batch.next_observations.row(i).transpose();
    double best_reward = -std::numeric_limits<double>::infinity();
    double best_cost = -std::numeric_limits<double>::infinity();
    for (int k = 0; k < m; ++k) {
      for (const bool reward : {true, false}) {
        const Eigen::MatrixXd& latents = reward ? reward_latents : cost_latents;
        const Eigen::VectorXd a = action_of(bcq, bcq.target_actor(), s, latents.row(i * m + k).transpose());
        double head[2];
        for (int h = 0; h < 2; ++h) {
          Mlp& first = reward ? bcq.target_reward_critic(2 * h) : bcq.target_cost_critic(2 * h);
          Mlp& second = reward ? bcq.target_reward_critic(2 * h + 1) : bcq.target_cost_critic(2 * h + 1);
          head[h] = std::min(q_of(first, s, a), q_of(second, s, a));
        }
        const double v = 0.75 * std::min(head[0], head[1]) + 0.25 * std::max(head[0], head[1]);
        (reward ? best_reward : best_cost) = std::max(reward ? best_reward : best_cost, v);
      }
    }
    const double bootstrap = o.gamma * (1.0 - batch.terminals[i]);
    EXPECT_NEAR(bcq.reward_targets()[i], o.reward_scale * batch.rewards[i] + bootstrap * best_reward, 1e-12) << i;
    EXPECT_NEAR(bcq.cost_targets()[i], o.cost_scale * batch.costs[i] + bootstrap * best_cost, 1e-12) << i;
  }
}

TEST(BcqLag, CriticLossByHandAndItsGradient) {
  Rng init(4), rng(5);
  BcqLag bcq(kObs, kAct, unit_scaling(), small_options(5.0), init);
  const OfflineBatch batch = random_batch(rng);
  const Eigen::VectorXd targets = Eigen::Vector4d(0.5, -1.0, 2.0, 0.1);
  Mlp& critic = bcq.cost_critic(3);
  double expected = 0.0;
  for (int i = 0; i < kRows; ++i) {
    const double e = q_of(critic, batch.observations.row(i).transpose(), batch.actions.row(i).transpose()) - targets[i];
    expected += e * e / kRows;
  }
  Eigen::VectorXd gradient(critic.num_parameters()), scratch(critic.num_parameters());
  EXPECT_NEAR(bcq.critic_loss(critic, batch, targets, gradient), expected, 1e-12);
  expect_central_differences(critic, gradient, [&] { return bcq.critic_loss(critic, batch, targets, scratch); });
}

TEST(BcqLag, ActorLossByHandAndItsGradient) {
  for (double multiplier : {0.0, 0.8}) {
    Rng init(6), rng(7);
    BcqLag bcq(kObs, kAct, unit_scaling(), small_options(5.0), init);
    const OfflineBatch batch = random_batch(rng);
    const Eigen::MatrixXd latents = 0.5 * normal_matrix(kRows, bcq.vae().latent_size(), rng);
    double expected = 0.0, mean_cost = 0.0;
    for (int i = 0; i < kRows; ++i) {
      const Eigen::VectorXd s = batch.observations.row(i).transpose();
      const Eigen::VectorXd a = action_of(bcq, bcq.actor(), s, latents.row(i).transpose());
      double q = std::numeric_limits<double>::infinity(), qc = q;
      for (int k = 0; k < kNets; ++k) {
        q = std::min(q, q_of(bcq.reward_critic(k), s, a));
        qc = std::min(qc, q_of(bcq.cost_critic(k), s, a));
      }
      expected += (-q + multiplier * (qc - bcq.options().cost_threshold())) / kRows;
      mean_cost += qc / kRows;
    }
    EXPECT_NEAR(bcq.actor_cost_estimate(batch, latents), mean_cost, 1e-12);
    Eigen::VectorXd gradient(bcq.actor().num_parameters()), scratch(bcq.actor().num_parameters());
    EXPECT_NEAR(bcq.actor_loss(batch, latents, multiplier, gradient), expected, 1e-12);
    EXPECT_GT(gradient.norm(), 0.0);
    expect_central_differences(bcq.actor(), gradient, [&] { return bcq.actor_loss(batch, latents, multiplier, scratch); });
  }
}

TEST(BcqLag, ActsWithTheProposalAtTheLatentsMeanOfTheStandardisedObservation) {
  Rng init(8);
  const ObservationScaling scaling{Eigen::Vector3d(1.0, -2.0, 0.0), Eigen::Vector3d(2.0, 4.0, 1.0)};
  BcqLag bcq(kObs, kAct, scaling, small_options(5.0), init);
  const std::vector<double> raw{3.0, 2.0, 0.5};
  std::vector<double> action(kAct);
  Rng unused(0);
  bcq.acting().act(raw, ActionMode::mean, unused, action);
  const Eigen::VectorXd expected = action_of(bcq, bcq.actor(), Eigen::Vector3d(1.0, 1.0, 0.5),
                                             Eigen::VectorXd::Zero(bcq.vae().latent_size()));
  for (int j = 0; j < kAct; ++j) EXPECT_NEAR(action[static_cast<std::size_t>(j)], expected[j], 1e-15);
}

TEST(BcqLag, SavedStateContinuesAsTheOriginal) {
  Rng init(10), rng(11);
  BcqLag trained(kObs, kAct, unit_scaling(), small_options(0.0), init);
  OfflineBatch batch = random_batch(rng);
  for (int u = 0; u < 3; ++u) trained.update(batch, rng);
  EXPECT_NE(trained.controller().previous_error, 0.0);
  BinaryWriter writer;
  trained.save(writer);
  Rng other(99);
  BcqLag loaded(kObs, kAct, ObservationScaling{Eigen::VectorXd::Ones(kObs), Eigen::VectorXd::Ones(kObs)},
                small_options(0.0), other);
  BinaryReader reader(writer.bytes(), "test");
  loaded.load(reader);
  reader.expect_end();
  EXPECT_EQ(loaded.controller().integral, trained.controller().integral);
  Rng a(12), b(12);
  EXPECT_EQ(loaded.update(batch, a), trained.update(batch, b));
  EXPECT_EQ(loaded.actor().parameters(), trained.actor().parameters());
  EXPECT_EQ(loaded.target_actor().parameters(), trained.target_actor().parameters());
  EXPECT_EQ(loaded.cost_critic(3).parameters(), trained.cost_critic(3).parameters());
  EXPECT_EQ(loaded.vae().decoder().parameters(), trained.vae().decoder().parameters());
}

TEST(BcqLag, RefusesOptionsOutOfRange) {
  Rng init(1);
  for (auto spoil : {+[](BcqLagOptions& o) { o.phi = 0.0; }, +[](BcqLagOptions& o) { o.lambda_mix = 1.5; },
                     +[](BcqLagOptions& o) { o.sampled_actions = 0; }, +[](BcqLagOptions& o) { o.pid_ki = -1.0; }}) {
    BcqLagOptions options = small_options(5.0);
    spoil(options);
    EXPECT_THROW(BcqLag(kObs, kAct, unit_scaling(), options, init), std::invalid_argument);
  }
}

}  // namespace bcq_lag_test
}  // namespace
}  // namespace bsg::algos
