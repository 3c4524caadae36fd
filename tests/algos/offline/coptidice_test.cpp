// COptiDICE (algos/offline/coptidice.h) against independent oracles: the three f-divergences and the
// identity f'((f')^{-1}(y)) = y; the dual L_nu on three rows worked out by hand for chi2 and softchi
// (networks at zero, so nu = 0); the ratios row by row from the networks' single-sample passes; each
// loss (nu, chi with its softmax weights, the weighted likelihood) against central differences; the
// upper bound's D_KL and C_hat written out; the acting policy's tanh(mu); the saved state continuing.
#include "algos/offline/coptidice.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "algos/offline/offline_batches.h"
#include "common/binary_io.h"
#include "offline_test_support.h"

namespace bsg::algos {
namespace {
namespace coptidice_test {

using testing::expect_central_differences;
using testing::normal_matrix;

constexpr int kObs = 3;
constexpr int kAct = 2;

COptiDiceOptions small_options(FDivergence f) {
  COptiDiceOptions options;
  options.hidden_sizes = {6};
  options.mlp = MlpOptions{};  // tanh: smooth for the central differences
  options.gamma = 0.9;
  options.alpha = 0.5;
  options.f_divergence = f;
  options.reward_scale = 1.0;
  options.cost_scale = 1.0;
  options.cost_limit = 5.0;
  options.episode_length = 20;
  options.initial_state_proportion = 0.25;
  options.action_std = Eigen::Vector2d(0.5, 2.0);
  return options;
}

ObservationScaling unit_scaling() { return testing::unit_scaling(kObs); }

OfflineBatch random_batch(Rng& rng, int rows) {
  OfflineBatch b;
  b.observations.resize(rows, kObs);
  b.next_observations.resize(rows, kObs);
  b.actions.resize(rows, kAct);
  for (Eigen::Index k = 0; k < b.observations.size(); ++k) b.observations.data()[k] = uniform(rng, -1.5, 1.5);
  for (Eigen::Index k = 0; k < b.next_observations.size(); ++k) b.next_observations.data()[k] = uniform(rng, -1.5, 1.5);
  for (Eigen::Index k = 0; k < b.actions.size(); ++k) b.actions.data()[k] = uniform(rng, -0.9, 0.9);
  b.rewards.resize(rows);
  b.costs.resize(rows);
  b.terminals.setZero(rows);
  b.initial.setZero(rows);
  for (int i = 0; i < rows; ++i) {
    b.rewards(i) = uniform(rng, -1.0, 2.0);
    b.costs(i) = i % 2;
  }
  b.terminals(1) = 1.0;
  b.initial(0) = 1.0;
  return b;
}

double nu_of(COptiDice& c, const Eigen::VectorXd& s) { return std::min(c.nu(0).forward(s)[0], c.nu(1).forward(s)[0]); }
double chi_of(COptiDice& c, const Eigen::VectorXd& s) { return std::min(c.chi(0).forward(s)[0], c.chi(1).forward(s)[0]); }

TEST(COptiDice, FDivergencesAreOsrlsAndTheirInverseDerivatives) {
  // chi2 at 3: (3 - 1)^2 / 2 = 2; softchi at 0.5: 0.5 (log 0.5 - 1) + 1 = 0.153426; kl at 2: 2 log 2.
  EXPECT_NEAR(f_divergence_value(FDivergence::chi2, 3.0), 2.0, 1e-15);
  EXPECT_NEAR(f_divergence_value(FDivergence::softchi, 0.5), 0.5 * (std::log(0.5) - 1.0) + 1.0, 1e-9);
  EXPECT_NEAR(f_divergence_value(FDivergence::softchi, 3.0), 2.0, 1e-15);
  EXPECT_NEAR(f_divergence_value(FDivergence::kl, 2.0), 2.0 * std::log(2.0), 1e-9);
  for (FDivergence f : {FDivergence::chi2, FDivergence::softchi, FDivergence::kl}) {
    for (double y : {-2.0, -0.3, 0.4, 1.7}) {
      const double x = f_divergence_derivative_inverse(f, y);
      EXPECT_NEAR(f_divergence_derivative(f, x), y, 1e-8) << static_cast<int>(f) << " " << y;
      const double h = 1e-6;
      EXPECT_NEAR(f_divergence_derivative_inverse_slope(f, y),
                  (f_divergence_derivative_inverse(f, y + h) - f_divergence_derivative_inverse(f, y - h)) / (2 * h), 1e-7);
    }
  }
}

// Every parameter 0: nu = chi = 0 and the actor's output 0.
void zero_networks(COptiDice& c) {
  for (Mlp* m : {&c.nu(0), &c.nu(1), &c.chi(0), &c.chi(1), &c.actor()}) m->set_parameters(Eigen::VectorXd::Zero(m->num_parameters()));
}

TEST(COptiDice, DualLossOnThreeRowsByHand) {
  // r = (0.5, -1, 0.2), c = (0, 1, 2), lambda = 1.5, alpha = 0.5, nu = 0: e = r - lambda c =
  // (0.5, -2.5, -2.8), e / alpha = (1, -5, -5.6).
  //   chi2:    w = max(0, e/alpha + 1) = (2, 0, 0); w e - alpha (w - 1)^2 / 2 = (1 - 0.25, -0.25, -0.25);
  //            L_nu = (0.75 - 0.25 - 0.25) / 3 = 1/12.
  //   softchi: w = (2, e^-5, e^-5.6); row 1: 1 - 0.25 = 0.75; rows 2, 3: w e - alpha (w (log w - 1) + 1)
  //            = w y alpha - alpha (w y - w + 1) = alpha (w - 1) with y = log w:
  //            L_nu = (0.75 + 0.5 (e^-5 - 1) + 0.5 (e^-5.6 - 1)) / 3.
  OfflineBatch b;
  b.observations.setZero(3, kObs);
  b.next_observations.setZero(3, kObs);
  b.actions.setZero(3, kAct);
  b.rewards = Eigen::Vector3d(0.5, -1.0, 0.2);
  b.costs = Eigen::Vector3d(0.0, 1.0, 2.0);
  b.terminals.setZero(3);
  b.initial = Eigen::Vector3d(1.0, 0.0, 0.0);
  for (FDivergence f : {FDivergence::chi2, FDivergence::softchi}) {
    Rng init(1);
    COptiDice c(kObs, kAct, unit_scaling(), small_options(f), init);
    zero_networks(c);
    std::vector<Eigen::VectorXd> gradients;
    const double loss = c.nu_loss(b, 1.5, gradients);
    const double expected = f == FDivergence::chi2
                                ? 1.0 / 12.0
                                : (0.75 + 0.5 * (std::exp(-5.0) - 1.0) + 0.5 * (std::exp(-5.6) - 1.0)) / 3.0;
    EXPECT_NEAR(loss, expected, 1e-9) << static_cast<int>(f);
    EXPECT_NEAR(c.ratios()[0], 2.0, 1e-15);
  }
}

TEST(COptiDice, RatiosRowByRow) {
  Rng init(2), rng(3);
  COptiDice c(kObs, kAct, unit_scaling(), small_options(FDivergence::softchi), init);
  const OfflineBatch b = random_batch(rng, 5);
  c.compute_ratios(b, 0.7);
  for (int i = 0; i < 5; ++i) {
    const double e = b.rewards(i) - 0.7 * b.costs(i) +
                     0.9 * (1.0 - b.terminals(i)) * nu_of(c, b.next_observations.row(i).transpose()) -
                     nu_of(c, b.observations.row(i).transpose());
    const double y = e / 0.5;
    EXPECT_NEAR(c.advantages()[i], e, 1e-12);
    EXPECT_NEAR(c.ratios()[i], std::max(0.0, y < 0 ? std::exp(y) : y + 1.0), 1e-12);
  }
}

TEST(COptiDice, NuLossGradientsAgainstCentralDifferences) {
  for (FDivergence f : {FDivergence::chi2, FDivergence::softchi, FDivergence::kl}) {
    Rng init(4), rng(5);
    COptiDice c(kObs, kAct, unit_scaling(), small_options(f), init);
    const OfflineBatch b = random_batch(rng, 6);
    std::vector<Eigen::VectorXd> gradients, scratch;
    c.nu_loss(b, 0.8, gradients);
    for (int k = 0; k < 2; ++k) {
      expect_central_differences(c.nu(k), gradients[static_cast<std::size_t>(k)],
                                 [&] { return c.nu_loss(b, 0.8, scratch); });
    }
  }
}

TEST(COptiDice, ChiLossItsUpperBoundAndGradients) {
  Rng init(6), rng(7);
  COptiDice c(kObs, kAct, unit_scaling(), small_options(FDivergence::softchi), init);
  const int n = 5;
  const OfflineBatch b = random_batch(rng, n);
  const Eigen::VectorXd w = Eigen::VectorXd::LinSpaced(n, 0.2, 1.8);
  const double tau = 0.6;
  std::vector<Eigen::VectorXd> gradients, scratch;
  const double loss = c.chi_loss(b, w, tau, gradients);
  // By hand: ell, q = N softmax(ell / tau), L = mean q ell, D_KL = mean(q log q - q + 1), C = mean q w c.
  std::vector<double> ell(n), q(n);
  double z = 0.0;
  for (int i = 0; i < n; ++i) {
    const Eigen::VectorXd s = b.observations.row(i).transpose();
    ell[i] = (1 - 0.9) * b.initial(i) * chi_of(c, s) / 0.25 +
             w(i) * (b.costs(i) + 0.9 * (1 - b.terminals(i)) * chi_of(c, b.next_observations.row(i).transpose()) - chi_of(c, s));
    z += std::exp(ell[i] / tau);
  }
  double expected = 0.0, kl = 0.0, cost = 0.0;
  for (int i = 0; i < n; ++i) {
    q[i] = n * std::exp(ell[i] / tau) / z;
    expected += q[i] * ell[i] / n;
    kl += (q[i] * std::log(q[i]) - q[i] + 1.0) / n;
    cost += q[i] * w(i) * b.costs(i) / n;
  }
  EXPECT_NEAR(loss, expected, 1e-12);
  EXPECT_NEAR(c.upper_bound_kl(), kl, 1e-12);
  EXPECT_NEAR(c.upper_bound_cost(), cost, 1e-12);
  for (int k = 0; k < 2; ++k) {
    expect_central_differences(c.chi(k), gradients[static_cast<std::size_t>(k)], [&] { return c.chi_loss(b, w, tau, scratch); });
  }
}

TEST(COptiDice, WeightedLikelihoodByHandAndItsGradient) {
  Rng init(8), rng(9);
  COptiDice c(kObs, kAct, unit_scaling(), small_options(FDivergence::softchi), init);
  const int n = 4;
  const OfflineBatch b = random_batch(rng, n);
  const Eigen::VectorXd w = Eigen::Vector4d(0.5, 0.0, 2.0, 1.2);
  const Eigen::MatrixXd obs_noise = normal_matrix(n, kObs, rng);
  const Eigen::MatrixXd act_noise = normal_matrix(n, kAct, rng);
  double expected = 0.0;
  for (int i = 0; i < n; ++i) {
    const Eigen::VectorXd out = c.actor().forward((b.observations.row(i) + 0.1 * obs_noise.row(i)).transpose());
    double log_prob = 0.0;
    for (int j = 0; j < kAct; ++j) {
      const double a = std::clamp(b.actions(i, j) + 0.1 * c.options().action_std(j) * act_noise(i, j), -1 + 1e-4, 1 - 1e-4);
      const double u = 0.5 * std::log((1 + a) / (1 - a));
      const double sigma = std::exp(std::clamp(out[kAct + j], -20.0, 2.0));
      log_prob += -0.5 * std::pow((u - out[j]) / sigma, 2) - std::log(sigma) - 0.5 * std::log(2 * M_PI) - std::log(1 - a * a);
    }
    expected -= w(i) * log_prob / n;
  }
  Eigen::VectorXd gradient(c.actor().num_parameters()), scratch(c.actor().num_parameters());
  EXPECT_NEAR(c.actor_loss(b, w, obs_noise, act_noise, gradient), expected, 1e-12);
  expect_central_differences(c.actor(), gradient, [&] { return c.actor_loss(b, w, obs_noise, act_noise, scratch); });
}

TEST(COptiDice, ActsWithTanhMuOfTheStandardisedObservation) {
  Rng init(10);
  const ObservationScaling scaling{Eigen::Vector3d(1.0, -2.0, 0.0), Eigen::Vector3d(2.0, 4.0, 1.0)};
  COptiDice c(kObs, kAct, scaling, small_options(FDivergence::softchi), init);
  const std::vector<double> raw{3.0, 2.0, 0.5};
  std::vector<double> action(kAct);
  Rng unused(0);
  c.acting().act(raw, ActionMode::mean, unused, action);
  const Eigen::VectorXd out = c.actor().forward(Eigen::Vector3d(1.0, 1.0, 0.5));
  for (int j = 0; j < kAct; ++j) EXPECT_DOUBLE_EQ(action[static_cast<std::size_t>(j)], std::tanh(out[j]));
}

TEST(COptiDice, SavedStateContinuesAsTheOriginal) {
  Rng init(11), rng(12);
  COptiDice trained(kObs, kAct, unit_scaling(), small_options(FDivergence::softchi), init);
  const OfflineBatch b = random_batch(rng, 6);
  for (int u = 0; u < 3; ++u) trained.update(b, rng);
  EXPECT_NE(trained.lambda_parameter(), 1.0);
  EXPECT_NE(trained.tau_parameter(), 1.0);
  BinaryWriter writer;
  trained.save(writer);
  Rng other(99);
  COptiDiceOptions blank = small_options(FDivergence::softchi);
  blank.initial_state_proportion = 1.0;
  blank.action_std = Eigen::VectorXd();
  COptiDice loaded(kObs, kAct, ObservationScaling{Eigen::VectorXd::Ones(kObs), Eigen::VectorXd::Ones(kObs)}, blank, other);
  BinaryReader reader(writer.bytes(), "test");
  loaded.load(reader);
  reader.expect_end();
  EXPECT_EQ(loaded.options().initial_state_proportion, 0.25);
  Rng x(13), y(13);
  EXPECT_EQ(loaded.update(b, x), trained.update(b, y));
  EXPECT_EQ(loaded.actor().parameters(), trained.actor().parameters());
  EXPECT_EQ(loaded.chi(1).parameters(), trained.chi(1).parameters());
  EXPECT_EQ(loaded.lambda_parameter(), trained.lambda_parameter());
}

TEST(COptiDice, InitialRowsAndActionSpreadOfTheTrainingRows) {
  // Two episodes, rows 0-2 (ended by a timeout) and 3-4 (a termination): first rows 0 and 3. Actions of
  // dimension 0: 0, 1, 0, 1, 0 (mean 0.4, variance 0.24); dimension 1: all 0.5 (standard deviation 0).
  OfflineDataset d;
  d.observation_dim = 1;
  d.action_dim = 2;
  for (int t = 0; t < 5; ++t) {
    d.observations.push_back(static_cast<float>(t));
    d.next_observations.push_back(static_cast<float>(t + 1));
    d.actions.push_back(static_cast<float>(t % 2));
    d.actions.push_back(0.5f);
    d.rewards.push_back(0.0f);
    d.costs.push_back(0.0f);
    d.terminals.push_back(t == 4 ? 1.0f : 0.0f);
    d.timeouts.push_back(t == 2 ? 1.0f : 0.0f);
  }
  const std::vector<char> first = episode_first_rows(d);
  EXPECT_EQ(first, (std::vector<char>{1, 0, 0, 1, 0}));
  const TrainingStatistics all = training_statistics(d, {0, 1, 2, 3, 4}, first);
  EXPECT_NEAR(all.initial_state_proportion, 0.4, 1e-15);
  EXPECT_NEAR(all.action_std[0], std::sqrt(0.24), 1e-7);
  EXPECT_EQ(all.action_std[1], 0.0);
  OfflineBatches batches(d, all_rows(d), 7);
  OfflineBatch batch;
  Rng rng(3);
  batches.sample(rng, batch);
  for (int i = 0; i < 7; ++i) {
    // the row's observation (standardised: mean 2, std sqrt 2) tells which row it is
    const int row = static_cast<int>(std::lround(batch.observations(i, 0) * std::sqrt(2.0) + 2.0));
    EXPECT_EQ(batch.initial(i), row == 0 || row == 3 ? 1.0 : 0.0) << row;
  }
}

TEST(COptiDice, RefusesOptionsOutOfRange) {
  Rng init(1);
  COptiDiceOptions options = small_options(FDivergence::kl);
  options.alpha = 0.0;
  EXPECT_THROW(COptiDice(kObs, kAct, unit_scaling(), options, init), std::invalid_argument);
  options = small_options(FDivergence::kl);
  options.action_std = Eigen::VectorXd::Ones(3);
  EXPECT_THROW(COptiDice(kObs, kAct, unit_scaling(), options, init), std::invalid_argument);
}

}  // namespace coptidice_test
}  // namespace
}  // namespace bsg::algos
