// The off-policy updates' derivatives against central differences (critic loss, SAC's actor loss
// through the squashing and its log-determinant, the deterministic actors' loss through dQ/da, the
// temperature loss), the critics' targets against the formula evaluated sample by sample, the
// target smoothing's clipping and Polyak averaging against hand computations.
#include "algos/off_policy/off_policy_learner.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "../../common/finite_differences.h"
#include "../../heap_counter.h"
#include "algos/off_policy/make_off_policy_learner.h"
#include "learner_test_support.h"
#include "algos/core/polyak.h"
#include "algos/core/squashed_gaussian.h"
#include "algos/off_policy/target_smoothing.h"
#include "algos/off_policy/temperature.h"

namespace bsg::algos {
namespace {
namespace off_policy_learner_test {

using learner_test::config_for;
using learner_test::perturb_targets;
using learner_test::random_matrix;

using testing::finite_difference_gradient;
using testing::relative_error;

constexpr int kObs = 3;
constexpr int kAct = 2;
constexpr int kRows = 7;

ReplayBatch random_batch(Rng& rng, int cost_count) {
  ReplayBatch batch;
  batch.observations = random_matrix(kRows, kObs, rng);
  batch.actions = random_matrix(kRows, kAct, rng, 0.9);
  batch.rewards = random_matrix(kRows, 1, rng);
  batch.costs = random_matrix(kRows, cost_count, rng).cwiseAbs();
  batch.next_observations = random_matrix(kRows, kObs, rng);
  batch.discounts = Eigen::VectorXd::Constant(kRows, 0.9);
  batch.discounts(2) = 0.81;  // a two-step transition
  batch.terminals = Eigen::VectorXd::Zero(kRows);
  batch.terminals(4) = 1.0;
  return batch;
}

TEST(SquashedGaussian, LogProbabilityIsTheGaussiansMinusTheSquashingsLogDeterminant) {
  Rng rng(1);
  const Eigen::MatrixXd outputs = random_matrix(kRows, 2 * kAct, rng, 1.5);
  const Eigen::MatrixXd noise = random_matrix(kRows, kAct, rng, 2.0);
  SquashedGaussianSample sample;
  squashed_gaussian_sample(outputs, noise, sample);
  for (int i = 0; i < kRows; ++i) {
    double expected = 0.0;
    for (int j = 0; j < kAct; ++j) {
      const double mu = outputs(i, j), sigma = std::exp(outputs(i, kAct + j));
      const double u = mu + sigma * noise(i, j);
      const double gaussian = std::exp(-0.5 * std::pow((u - mu) / sigma, 2)) / (sigma * std::sqrt(2 * std::numbers::pi));
      expected += std::log(gaussian) - std::log(1.0 - std::pow(std::tanh(u), 2));
      EXPECT_NEAR(sample.actions(i, j), std::tanh(u), 1e-15);
    }
    EXPECT_NEAR(sample.log_probs(i), expected, 1e-9);
  }
}

TEST(SquashedGaussian, BackwardMatchesCentralDifferences) {
  Rng rng(2);
  Eigen::MatrixXd outputs = random_matrix(kRows, 2 * kAct, rng, 1.5);
  outputs(0, kAct) = -25.0;  // clamped log sigma: no gradient
  const Eigen::MatrixXd noise = random_matrix(kRows, kAct, rng, 2.0);
  const Eigen::MatrixXd action_weights = random_matrix(kRows, kAct, rng);
  const Eigen::VectorXd log_prob_weights = random_matrix(kRows, 1, rng);
  // L = sum w . a + sum v log pi
  const auto loss = [&](const Eigen::VectorXd& flat) {
    const Eigen::MatrixXd o = Eigen::Map<const Eigen::MatrixXd>(flat.data(), kRows, 2 * kAct);
    SquashedGaussianSample s;
    squashed_gaussian_sample(o, noise, s);
    return (s.actions.array() * action_weights.array()).sum() + s.log_probs.dot(log_prob_weights);
  };
  SquashedGaussianSample sample;
  squashed_gaussian_sample(outputs, noise, sample);
  Eigen::MatrixXd gradient(kRows, 2 * kAct);
  squashed_gaussian_backward(outputs, noise, sample, action_weights, log_prob_weights, gradient);
  const Eigen::VectorXd flat = Eigen::Map<const Eigen::VectorXd>(outputs.data(), outputs.size());
  const Eigen::VectorXd expected = finite_difference_gradient(loss, flat);
  EXPECT_LT(relative_error(Eigen::Map<const Eigen::VectorXd>(gradient.data(), gradient.size()), expected), 1e-7);
  EXPECT_EQ(gradient(0, kAct), 0.0);
}

void check_critic_loss(Algorithm alg) {
  Rng rng(3);
  const auto owned_learner = make_off_policy_learner(config_for(alg), kObs, kAct, 2, rng);
  OffPolicyLearner& learner = *owned_learner;
  const ReplayBatch batch = random_batch(rng, 2);
  const Eigen::VectorXd targets = random_matrix(kRows, 1, rng);
  Mlp& critic = learner.cost_critic(1);
  const Eigen::VectorXd theta = critic.parameters();
  Eigen::VectorXd gradient(theta.size());
  const double loss = learner.critic_loss(critic, batch, targets, gradient);
  // mean (Q(s, a) - y)^2, Q sample by sample
  double expected_loss = 0.0;
  for (int i = 0; i < kRows; ++i) {
    Eigen::VectorXd input(kObs + kAct);
    input << batch.observations.row(i).transpose(), batch.actions.row(i).transpose();
    expected_loss += std::pow(critic.forward(input)(0) - targets(i), 2) / kRows;
  }
  EXPECT_NEAR(loss, expected_loss, 1e-12);
  Eigen::VectorXd scratch(theta.size());
  const auto f = [&](const Eigen::VectorXd& parameters) {
    critic.set_parameters(parameters);
    return learner.critic_loss(critic, batch, targets, scratch);
  };
  const Eigen::VectorXd expected = finite_difference_gradient(f, theta);
  EXPECT_LT(relative_error(gradient, expected), 1e-7);
}

TEST(OffPolicyLearner, CriticLossGradientMatchesCentralDifferences) {
  check_critic_loss(Algorithm::sac_lag);
  check_critic_loss(Algorithm::ddpg_lag);
}

void check_actor_loss(Algorithm alg, const std::vector<double>& lambdas) {
  Rng rng(4);
  const int cost_count = static_cast<int>(lambdas.size());
  const auto owned_learner = make_off_policy_learner(config_for(alg), kObs, kAct, cost_count, rng);
  OffPolicyLearner& learner = *owned_learner;
  const ReplayBatch batch = random_batch(rng, cost_count);
  const Eigen::MatrixXd noise = random_matrix(kRows, kAct, rng, 1.5);
  const Eigen::VectorXd theta = learner.actor().parameters();
  Eigen::VectorXd gradient(theta.size());
  learner.actor_loss(batch, noise, lambdas, gradient, nullptr);
  Eigen::VectorXd scratch(theta.size());
  const auto f = [&](const Eigen::VectorXd& parameters) {
    learner.actor().set_parameters(parameters);
    return learner.actor_loss(batch, noise, lambdas, scratch, nullptr);
  };
  const Eigen::VectorXd expected = finite_difference_gradient(f, theta);
  EXPECT_LT(relative_error(gradient, expected), 1e-6) << to_string(alg);
}

TEST(OffPolicyLearner, SacActorLossGradientThroughTheSquashingMatchesCentralDifferences) {
  check_actor_loss(Algorithm::sac, {});
  check_actor_loss(Algorithm::sac_lag, {0.4, 1.7});
}

TEST(OffPolicyLearner, DeterministicActorLossGradientThroughDqDaMatchesCentralDifferences) {
  check_actor_loss(Algorithm::td3_lag, {0.4, 1.7});
  check_actor_loss(Algorithm::ddpg_lag, {0.0, 2.5});
  check_actor_loss(Algorithm::ddpg, {});
}

TEST(OffPolicyLearner, SacActorLossIsTheRescaledLagrangianOfTheSample) {
  Rng rng(5);
  const auto owned_learner = make_off_policy_learner(config_for(Algorithm::sac_lag), kObs, kAct, 1, rng);
  OffPolicyLearner& learner = *owned_learner;
  const ReplayBatch batch = random_batch(rng, 1);
  const Eigen::MatrixXd noise = random_matrix(kRows, kAct, rng);
  Eigen::VectorXd gradient(learner.actor().num_parameters());
  const std::vector<double> lambdas{0.6};
  double log_prob_mean = 0.0;
  const double loss = learner.actor_loss(batch, noise, lambdas, gradient, &log_prob_mean);
  // mean [alpha log pi - min(Q1, Q2) + lambda Qc] / (1 + lambda), sample by sample
  double expected = 0.0, expected_log_prob = 0.0;
  for (int i = 0; i < kRows; ++i) {
    const Eigen::VectorXd out = learner.actor().forward(Eigen::VectorXd(batch.observations.row(i).transpose()));
    Eigen::VectorXd input(kObs + kAct);
    input.head(kObs) = batch.observations.row(i).transpose();
    double log_prob = 0.0;
    for (int j = 0; j < kAct; ++j) {
      const double sigma = std::exp(out(kAct + j));
      const double u = out(j) + sigma * noise(i, j);
      input(kObs + j) = std::tanh(u);
      log_prob += -0.5 * noise(i, j) * noise(i, j) - std::log(sigma) - 0.5 * std::log(2 * std::numbers::pi) -
                  std::log(1 - std::pow(std::tanh(u), 2));
    }
    const double q = std::min(learner.reward_critic(0).forward(input)(0), learner.reward_critic(1).forward(input)(0));
    const double qc = learner.cost_critic(0).forward(input)(0);
    expected += (0.3 * log_prob - q + 0.6 * qc) / (1.6 * kRows);
    expected_log_prob += log_prob / kRows;
  }
  EXPECT_NEAR(loss, expected, 1e-10);
  EXPECT_NEAR(log_prob_mean, expected_log_prob, 1e-10);
}

TEST(Temperature, LossGradientIsMinusTheEntropyShortfall) {
  const Temperature temperature(/*alpha_init=*/0.3, /*alpha_lr=*/3e-4, /*target_entropy=*/-2.0);
  // L(log alpha) = -log alpha (E log pi + H_target), H_target = -|A| = -2
  double gradient = 0.0;
  const double loss = temperature.loss(-0.3, &gradient);
  EXPECT_DOUBLE_EQ(gradient, 2.3);
  EXPECT_DOUBLE_EQ(loss, -std::log(0.3) * (-2.3));
  // central differences in log alpha of the same expression
  const double h = 1e-6;
  const double la = temperature.log_alpha();
  const double fd = ((-(la + h) * (-2.3)) - (-(la - h) * (-2.3))) / (2 * h);
  EXPECT_NEAR(gradient, fd, 1e-8);
}

TEST(OffPolicyLearner, AutoAlphaLowersTheTemperatureWhenTheEntropyIsAboveTarget) {
  RunConfig config;
  config.alg = Algorithm::sac;
  config.hidden_sizes = {6, 5};
  config.dtype = Dtype::float64;
  config.off_policy.auto_alpha = true;
  config.off_policy.alpha_lr = 0.01;
  config.off_policy.policy_delay = 1;
  Rng rng(7);
  const auto owned_learner = make_off_policy_learner(config, kObs, kAct, 0, rng);
  OffPolicyLearner& learner = *owned_learner;
  const ReplayBatch batch = random_batch(rng, 0);
  const double before = learner.alpha();
  // A fresh actor has sigma near 1: entropy far above -|A|, so log pi + H_target < 0 and alpha falls.
  learner.update(batch, {}, rng, MpiContext::single_process());
  EXPECT_LT(learner.alpha(), before);
  // Adam's first step moves log alpha by lr exactly (m_hat / sqrt(v_hat) = sign of the gradient).
  EXPECT_NEAR(std::log(learner.alpha()), std::log(before) - 0.01, 1e-9);
}

TEST(OffPolicyLearner, DdpgTargetsBootstrapFromTheTargetNetsUnlessTerminal) {
  Rng rng(8);
  const auto owned_learner = make_off_policy_learner(config_for(Algorithm::ddpg_lag), kObs, kAct, 1, rng);
  OffPolicyLearner& learner = *owned_learner;
  perturb_targets(learner, rng);
  const ReplayBatch batch = random_batch(rng, 1);
  learner.compute_targets(batch, Eigen::MatrixXd::Zero(kRows, kAct));
  for (int i = 0; i < kRows; ++i) {
    const Eigen::VectorXd next = batch.next_observations.row(i).transpose();
    Eigen::VectorXd input(kObs + kAct);
    input << next, learner.target_actor().forward(next).array().tanh().matrix();
    const double bootstrap = batch.terminals(i) == 1.0 ? 0.0 : batch.discounts(i);
    EXPECT_NEAR(learner.reward_targets()(i),
                batch.rewards(i) + bootstrap * learner.target_reward_critic(0).forward(input)(0), 1e-12);
    EXPECT_NEAR(learner.cost_targets()(i, 0),
                batch.costs(i, 0) + bootstrap * learner.target_cost_critic(0).forward(input)(0), 1e-12);
  }
  EXPECT_DOUBLE_EQ(learner.reward_targets()(4), batch.rewards(4));  // terminal: y = R
}

TEST(OffPolicyLearner, SacTargetsUseTheSoftValueOfTheTwinMinimum) {
  Rng rng(9);
  const auto owned_learner = make_off_policy_learner(config_for(Algorithm::sac_lag), kObs, kAct, 1, rng);
  OffPolicyLearner& learner = *owned_learner;
  perturb_targets(learner, rng);
  const ReplayBatch batch = random_batch(rng, 1);
  const Eigen::MatrixXd noise = random_matrix(kRows, kAct, rng);
  learner.compute_targets(batch, noise);
  for (int i = 0; i < kRows; ++i) {
    const Eigen::VectorXd next = batch.next_observations.row(i).transpose();
    const Eigen::VectorXd out = learner.actor().forward(next);
    Eigen::VectorXd input(kObs + kAct);
    input.head(kObs) = next;
    double log_prob = 0.0;
    for (int j = 0; j < kAct; ++j) {
      const double sigma = std::exp(out(kAct + j));
      const double u = out(j) + sigma * noise(i, j);
      input(kObs + j) = std::tanh(u);
      log_prob += -0.5 * noise(i, j) * noise(i, j) - std::log(sigma) - 0.5 * std::log(2 * std::numbers::pi) -
                  std::log(1 - std::pow(std::tanh(u), 2));
    }
    const double q = std::min(learner.target_reward_critic(0).forward(input)(0),
                              learner.target_reward_critic(1).forward(input)(0));
    const double bootstrap = batch.terminals(i) == 1.0 ? 0.0 : batch.discounts(i);
    EXPECT_NEAR(learner.reward_targets()(i), batch.rewards(i) + bootstrap * (q - 0.3 * log_prob), 1e-10);
    // the cost target has no entropy term
    EXPECT_NEAR(learner.cost_targets()(i, 0),
                batch.costs(i, 0) + bootstrap * learner.target_cost_critic(0).forward(input)(0), 1e-10);
  }
}

TEST(TargetSmoothing, ClipsTheNoiseThenTheAction) {
  // policy_noise 0.2, noise_clip 0.5
  Eigen::MatrixXd actions(1, 4);
  actions << 0.9, 0.0, -0.2, 0.3;
  Eigen::MatrixXd noise(1, 4);
  noise << 1.0, 3.0, -4.0, -1.0;  // 0.2, 0.6 -> 0.5, -0.8 -> -0.5, -0.2
  smooth_target_actions(actions, noise, 0.2, 0.5);
  EXPECT_DOUBLE_EQ(actions(0, 0), 1.0);  // 1.1 clipped to the action bound
  EXPECT_DOUBLE_EQ(actions(0, 1), 0.5);
  EXPECT_DOUBLE_EQ(actions(0, 2), -0.7);
  EXPECT_DOUBLE_EQ(actions(0, 3), 0.1);
}

TEST(Polyak, MovesTheTargetATauOfTheWayToTheOnlineNet) {
  Eigen::VectorXd target(3), online(3);
  target << 1.0, -2.0, 0.0;
  online << 3.0, 2.0, 8.0;
  polyak_update(target, online, 0.25);
  EXPECT_DOUBLE_EQ(target(0), 1.5);
  EXPECT_DOUBLE_EQ(target(1), -1.0);
  EXPECT_DOUBLE_EQ(target(2), 2.0);
}

TEST(OffPolicyLearner, Td3UpdatesActorAndTargetsEveryPolicyDelaySteps) {
  RunConfig config;
  config.alg = Algorithm::td3;
  config.hidden_sizes = {6, 5};
  config.dtype = Dtype::float64;
  config.off_policy.policy_delay = 2;
  Rng rng(10);
  const auto owned_learner = make_off_policy_learner(config, kObs, kAct, 0, rng);
  OffPolicyLearner& learner = *owned_learner;
  const ReplayBatch batch = random_batch(rng, 0);
  const Eigen::VectorXd actor0 = learner.actor().parameters();
  const Eigen::VectorXd target0 = learner.target_reward_critic(0).parameters();
  const OffPolicyStepStats first = learner.update(batch, {}, rng, MpiContext::single_process());
  EXPECT_FALSE(first.actor_updated);
  EXPECT_EQ(learner.actor().parameters(), actor0);
  EXPECT_EQ(learner.target_reward_critic(0).parameters(), target0);
  const Eigen::VectorXd critic_after_two_steps_pending = learner.reward_critic(0).parameters();
  const OffPolicyStepStats second = learner.update(batch, {}, rng, MpiContext::single_process());
  EXPECT_TRUE(second.actor_updated);
  EXPECT_NE(learner.actor().parameters(), actor0);
  // target <- 0.995 target + 0.005 online (the critic after its second step)
  const Eigen::VectorXd expected = 0.995 * target0 + 0.005 * learner.reward_critic(0).parameters();
  EXPECT_LT((learner.target_reward_critic(0).parameters() - expected).norm(), 1e-12);
  (void)critic_after_two_steps_pending;
}

TEST(OffPolicyLearner, SaveAndLoadRestoreEveryNetworkAndOptimiser) {
  Rng rng(11);
  const auto owned_learner = make_off_policy_learner(config_for(Algorithm::sac_lag), kObs, kAct, 1, rng);
  OffPolicyLearner& learner = *owned_learner;
  const ReplayBatch batch = random_batch(rng, 1);
  const std::vector<double> lambdas{0.5};
  learner.update(batch, lambdas, rng, MpiContext::single_process());
  BinaryWriter writer;
  learner.save(writer);
  Rng other_rng(99);
  const auto owned_restored = make_off_policy_learner(config_for(Algorithm::sac_lag), kObs, kAct, 1, other_rng);
  OffPolicyLearner& restored = *owned_restored;
  BinaryReader reader(writer.bytes(), "test");
  restored.load(reader);
  reader.expect_end();
  Rng a(5), b(5);
  learner.update(batch, lambdas, a, MpiContext::single_process());
  restored.update(batch, lambdas, b, MpiContext::single_process());
  EXPECT_EQ(learner.actor().parameters(), restored.actor().parameters());
  EXPECT_EQ(learner.target_cost_critic(0).parameters(), restored.target_cost_critic(0).parameters());
  EXPECT_EQ(learner.update_count(), restored.update_count());
}

TEST(OffPolicyLearner, AGradientStepAllocatesNothingOnceSized) {
  if (!testing::heap_calls_countable()) GTEST_SKIP() << "heap calls are not countable here (AddressSanitizer)";
  for (const Algorithm alg : {Algorithm::sac_lag, Algorithm::td3_lag, Algorithm::ddpg_lag}) {
    SCOPED_TRACE(std::string(to_string(alg)));
    RunConfig config;
    config.alg = alg;
    config.hidden_sizes = {32, 32};
    config.off_policy.auto_alpha = true;
    config.off_policy.policy_delay = 2;
    Rng rng(12);
    const auto owned_learner = make_off_policy_learner(config, kObs, kAct, 2, rng);
    OffPolicyLearner& learner = *owned_learner;
    const ReplayBatch batch = random_batch(rng, 2);
    const std::vector<double> lambdas{0.3, 0.0};
    const MpiContext mpi = MpiContext::single_process();
    OffPolicyStepStats stats;
    for (int step = 0; step < 2; ++step) learner.update(batch, lambdas, rng, mpi, stats);  // sizes everything
    const long allocations = testing::allocations_of([&] {
      for (int step = 0; step < 4; ++step) learner.update(batch, lambdas, rng, mpi, stats);
    });
    EXPECT_EQ(allocations, 0);
  }
}

}  // namespace off_policy_learner_test
}  // namespace
}  // namespace bsg::algos
