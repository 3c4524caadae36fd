// CPQ (algos/offline/cpq.h) against independent oracles: the threshold l of OSRL's formula in
// figures; the critics' targets computed row by row from the networks' single-sample passes; the
// out-of-distribution flags from hand-computed latent KLs and their 0.75 quantile; each loss written
// out sample by sample and its gradient against central differences; the acting policy's tanh(mu)
// through the standardisation; the saved state continuing as the original; and the factory.
#include "algos/offline/cpq.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "algos/offline/make_offline_algorithm.h"
#include "common/binary_io.h"
#include "offline_test_support.h"

namespace bsg::algos {
namespace {
namespace cpq_test {

using testing::expect_central_differences;
using testing::normal_matrix;
using testing::q_of;

constexpr int kObs = 3;
constexpr int kAct = 2;
constexpr int kRows = 4;

CpqOptions small_options(double cost_limit) {
  CpqOptions options;
  testing::set_small_vae_learner_options(options, cost_limit);
  return options;
}

ObservationScaling unit_scaling() { return testing::unit_scaling(kObs); }

OfflineBatch random_batch(Rng& rng) { return testing::random_offline_batch(rng, kObs, kAct); }

// Moves every target critic away from its online copy, so that the targets' use is seen.
void perturb_targets(Cpq& cpq, Rng& rng) {
  for (int k = 0; k < 2; ++k) {
    for (Mlp* target : {&cpq.target_reward_critic(k), &cpq.target_cost_critic(k)}) {
      Eigen::VectorXd p = target->parameters();
      for (Eigen::Index i = 0; i < p.size(); ++i) p[i] += 0.3 * standard_normal(rng);
      target->set_parameters(p);
    }
  }
}

// The squashed sample tanh(mu + sigma eps) of one row, from the actor's single-sample pass.
Eigen::VectorXd squashed(Mlp& actor, const Eigen::VectorXd& s, const Eigen::VectorXd& eps) {
  const Eigen::VectorXd out = actor.forward(s);
  Eigen::VectorXd a(kAct);
  for (int j = 0; j < kAct; ++j) a[j] = std::tanh(out[j] + std::exp(std::clamp(out[kAct + j], -20.0, 2.0)) * eps[j]);
  return a;
}

TEST(Cpq, ThresholdIsOsrls) {
  CpqOptions options;  // d = 10, gamma = 0.99, T = 300: 10 (1 - 0.99^300) / (0.01 * 300)
  EXPECT_NEAR(options.cost_threshold(), 3.16986, 1e-5);
  options.gamma = 0.9;
  options.episode_length = 2;
  options.cost_limit = 4.0;  // 4 (1 - 0.81) / (0.1 * 2) = 3.8
  EXPECT_NEAR(options.cost_threshold(), 3.8, 1e-12);
  options.gamma = 1.0;  // undiscounted: l = d
  EXPECT_EQ(options.cost_threshold(), 4.0);
}

TEST(Cpq, TargetsRowByRow) {
  // l = 0: whether a row's next action counts as safe depends on the sign of min Qc'.
  for (double cost_limit : {0.0, 1000.0}) {
    Rng init(1), rng(2);
    Cpq cpq(kObs, kAct, unit_scaling(), small_options(cost_limit), init);
    perturb_targets(cpq, rng);
    const OfflineBatch batch = random_batch(rng);
    const Eigen::MatrixXd next_noise = normal_matrix(kRows, kAct, rng);
    cpq.compute_targets(batch, next_noise);
    const CpqOptions& o = cpq.options();
    for (int i = 0; i < kRows; ++i) {
      const Eigen::VectorXd s = batch.next_observations.row(i).transpose();
      const Eigen::VectorXd a = squashed(cpq.actor(), s, next_noise.row(i).transpose());
      const double q = std::min(q_of(cpq.target_reward_critic(0), s, a), q_of(cpq.target_reward_critic(1), s, a));
      const double qc = std::min(q_of(cpq.target_cost_critic(0), s, a), q_of(cpq.target_cost_critic(1), s, a));
      const double bootstrap = o.gamma * (1.0 - batch.terminals[i]);
      const double safe = qc <= o.cost_threshold() ? 1.0 : 0.0;
      EXPECT_NEAR(cpq.reward_targets()[i], o.reward_scale * batch.rewards[i] + bootstrap * safe * q, 1e-12) << i;
      EXPECT_NEAR(cpq.cost_targets()[i], o.cost_scale * batch.costs[i] + bootstrap * qc, 1e-12) << i;
    }
  }
}

TEST(Cpq, OutOfDistributionFlagsAreTheTopQuarterOfTheLatentKl) {
  Rng init(3), rng(4);
  Cpq cpq(kObs, kAct, unit_scaling(), small_options(5.0), init);
  const OfflineBatch batch = random_batch(rng);
  const int m = cpq.options().sampled_actions;
  const Eigen::MatrixXd noise = normal_matrix(kRows * m, kAct, rng);
  cpq.sample_out_of_distribution(batch, noise);
  // By hand: sample j of row i is row j N + i; its KL from the encoder's single-sample pass.
  std::vector<double> kl;
  for (int j = 0; j < m; ++j) {
    for (int i = 0; i < kRows; ++i) {
      const Eigen::VectorXd s = batch.observations.row(i).transpose();
      const Eigen::VectorXd a = squashed(cpq.actor(), s, noise.row(j * kRows + i).transpose());
      Eigen::VectorXd input(kObs + kAct);
      input << s, a;
      EXPECT_NEAR((cpq.ood_inputs().row(j * kRows + i).transpose() - input).norm(), 0.0, 1e-14);
      const Eigen::VectorXd out = cpq.vae().encoder().forward(input);
      const int latent = cpq.vae().latent_size();
      double sum = 0.0;
      for (int l = 0; l < latent; ++l) {
        const double log_std = std::clamp(out[latent + l], -4.0, 15.0);
        sum += -0.5 * (1.0 + 2.0 * log_std - out[l] * out[l] - std::exp(2.0 * log_std));
      }
      kl.push_back(sum / latent);
    }
  }
  // 12 values: the 0.75 quantile lies at position 8.25 of the sorted list.
  std::vector<double> sorted = kl;
  std::sort(sorted.begin(), sorted.end());
  const double quantile = sorted[8] + 0.25 * (sorted[9] - sorted[8]);
  int flagged = 0;
  for (std::size_t k = 0; k < kl.size(); ++k) {
    EXPECT_EQ(cpq.ood_flags()[static_cast<Eigen::Index>(k)], kl[k] >= quantile ? 1.0 : 0.0) << k;
    flagged += kl[k] >= quantile ? 1 : 0;
  }
  EXPECT_EQ(flagged, 3);  // the three values above position 8.25
}

TEST(Cpq, CriticLossesByHandAndTheirGradients) {
  Rng init(5), rng(6);
  Cpq cpq(kObs, kAct, unit_scaling(), small_options(5.0), init);
  const OfflineBatch batch = random_batch(rng);
  const Eigen::VectorXd targets = Eigen::Vector4d(0.5, -1.0, 2.0, 0.1);
  cpq.sample_out_of_distribution(batch, normal_matrix(kRows * cpq.options().sampled_actions, kAct, rng));
  const double alpha = 0.7;
  const double l_ood = cpq.options().qc_scalar * cpq.options().cost_threshold();
  for (double weight : {0.0, alpha}) {
    Mlp& critic = weight == 0.0 ? cpq.reward_critic(1) : cpq.cost_critic(0);
    // mean (Q(s, a) - y)^2 - alpha (mean o Q(s, a_m) - l_ood), sample by sample.
    double expected = 0.0;
    for (int i = 0; i < kRows; ++i) {
      const double e = q_of(critic, batch.observations.row(i).transpose(), batch.actions.row(i).transpose()) - targets[i];
      expected += e * e / kRows;
    }
    if (weight != 0.0) {
      double ood = 0.0;
      const Eigen::Index n = cpq.ood_inputs().rows();
      for (Eigen::Index k = 0; k < n; ++k) ood += cpq.ood_flags()[k] * critic.forward(cpq.ood_inputs().row(k).transpose())[0];
      expected -= weight * (ood / static_cast<double>(n) - l_ood);
    }
    Eigen::VectorXd gradient(critic.num_parameters()), scratch(critic.num_parameters());
    EXPECT_NEAR(cpq.critic_loss(critic, batch, targets, weight, gradient), expected, 1e-12);
    expect_central_differences(critic, gradient, [&] { return cpq.critic_loss(critic, batch, targets, weight, scratch); });
  }
}

TEST(Cpq, ActorLossByHandAndItsGradient) {
  // l large enough that every row is safe, and l = 0, where the cost critics' sign decides.
  for (double cost_limit : {1000.0, 0.0}) {
    Rng init(7), rng(8);
    Cpq cpq(kObs, kAct, unit_scaling(), small_options(cost_limit), init);
    const OfflineBatch batch = random_batch(rng);
    const Eigen::MatrixXd noise = normal_matrix(kRows, kAct, rng);
    double expected = 0.0;
    for (int i = 0; i < kRows; ++i) {
      const Eigen::VectorXd s = batch.observations.row(i).transpose();
      const Eigen::VectorXd a = squashed(cpq.actor(), s, noise.row(i).transpose());
      const double q = std::min(q_of(cpq.reward_critic(0), s, a), q_of(cpq.reward_critic(1), s, a));
      const double qc = std::min(q_of(cpq.cost_critic(0), s, a), q_of(cpq.cost_critic(1), s, a));
      if (qc <= cpq.options().cost_threshold()) expected -= q / kRows;
    }
    Eigen::VectorXd gradient(cpq.actor().num_parameters()), scratch(cpq.actor().num_parameters());
    EXPECT_NEAR(cpq.actor_loss(batch, noise, gradient), expected, 1e-12);
    expect_central_differences(cpq.actor(), gradient, [&] { return cpq.actor_loss(batch, noise, scratch); });
  }
}

TEST(Cpq, ActsWithTanhMuOfTheStandardisedObservation) {
  Rng init(9);
  const ObservationScaling scaling{Eigen::Vector3d(1.0, -2.0, 0.0), Eigen::Vector3d(2.0, 4.0, 1.0)};
  Cpq cpq(kObs, kAct, scaling, small_options(5.0), init);
  const std::vector<double> raw{3.0, 2.0, 0.5};
  std::vector<double> action(kAct);
  Rng unused(0);
  cpq.acting().act(raw, ActionMode::mean, unused, action);
  const Eigen::VectorXd out = cpq.actor().forward(Eigen::Vector3d(1.0, 1.0, 0.5));  // (3-1)/2, (2+2)/4, 0.5
  for (int j = 0; j < kAct; ++j) EXPECT_DOUBLE_EQ(action[static_cast<std::size_t>(j)], std::tanh(out[j]));
}

TEST(Cpq, SavedStateContinuesAsTheOriginal) {
  Rng init(10), rng(11);
  Cpq trained(kObs, kAct, unit_scaling(), small_options(5.0), init);
  OfflineBatch batch = random_batch(rng);
  for (int u = 0; u < 3; ++u) trained.update(batch, rng);
  EXPECT_NE(trained.log_alpha(), 0.0);
  BinaryWriter writer;
  trained.save(writer);
  Rng other(99);
  Cpq loaded(kObs, kAct, ObservationScaling{Eigen::VectorXd::Ones(kObs), Eigen::VectorXd::Ones(kObs)},
             small_options(5.0), other);
  BinaryReader reader(writer.bytes(), "test");
  loaded.load(reader);
  reader.expect_end();
  EXPECT_EQ(loaded.log_alpha(), trained.log_alpha());
  Rng a(12), b(12);
  EXPECT_EQ(loaded.update(batch, a), trained.update(batch, b));
  EXPECT_EQ(loaded.actor().parameters(), trained.actor().parameters());
  EXPECT_EQ(loaded.cost_critic(1).parameters(), trained.cost_critic(1).parameters());
  EXPECT_EQ(loaded.vae().decoder().parameters(), trained.vae().decoder().parameters());
}

TEST(Cpq, RefusesOptionsOutOfRange) {
  Rng init(1);
  CpqOptions options = small_options(5.0);
  options.sampled_actions = 0;
  EXPECT_THROW(Cpq(kObs, kAct, unit_scaling(), options, init), std::invalid_argument);
  options = small_options(5.0);
  options.tau = 0.0;
  EXPECT_THROW(Cpq(kObs, kAct, unit_scaling(), options, init), std::invalid_argument);
}

}  // namespace cpq_test
}  // namespace
}  // namespace bsg::algos
