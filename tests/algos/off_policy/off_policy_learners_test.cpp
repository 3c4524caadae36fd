// The learners over the off-policy base (sac_learner.h, td3_learner.h, ddpg_learner.h) through their
// hooks, each against the formula evaluated sample by sample: which learner an algorithm gets, how
// each acts, TD3's smoothed twin target, the deterministic actors' loss on Q_1 alone, and the
// temperature slot the deterministic actors fill in the checkpoint.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "algos/off_policy/make_off_policy_learner.h"
#include "learner_test_support.h"
#include "algos/off_policy/off_policy_learner.h"

namespace bsg::algos {
namespace {
namespace off_policy_learners_test {

using learner_test::config_for;
using learner_test::perturb_targets;
using learner_test::random_matrix;

constexpr int kObs = 3;
constexpr int kAct = 2;
constexpr int kRows = 6;

ReplayBatch random_batch(Rng& rng, int cost_count) {
  ReplayBatch batch;
  batch.observations = random_matrix(kRows, kObs, rng);
  batch.actions = random_matrix(kRows, kAct, rng, 0.9);
  batch.rewards = random_matrix(kRows, 1, rng);
  batch.costs = random_matrix(kRows, cost_count, rng).cwiseAbs();
  batch.next_observations = random_matrix(kRows, kObs, rng);
  batch.discounts = Eigen::VectorXd::Constant(kRows, 0.9);
  batch.terminals = Eigen::VectorXd::Zero(kRows);
  batch.terminals(3) = 1.0;
  return batch;
}

Eigen::VectorXd critic_input(const Eigen::VectorXd& observation, const Eigen::VectorXd& action) {
  Eigen::VectorXd input(observation.size() + action.size());
  input << observation, action;
  return input;
}

TEST(MakeOffPolicyLearner, GivesEachAlgorithmItsActorCriticsAndTemperature) {
  struct Expected {
    Algorithm alg;
    ActorKind kind;
    int reward_critics;
    int actor_outputs;
    bool temperature;
  };
  for (const Expected& e : {Expected{Algorithm::sac, ActorKind::squashed_gaussian, 2, 2 * kAct, true},
                            Expected{Algorithm::sac_lag, ActorKind::squashed_gaussian, 2, 2 * kAct, true},
                            Expected{Algorithm::td3, ActorKind::deterministic, 2, kAct, false},
                            Expected{Algorithm::td3_lag, ActorKind::deterministic, 2, kAct, false},
                            Expected{Algorithm::ddpg, ActorKind::deterministic, 1, kAct, false},
                            Expected{Algorithm::ddpg_lag, ActorKind::deterministic, 1, kAct, false}}) {
    SCOPED_TRACE(std::string(to_string(e.alg)));
    Rng rng(1);
    const auto learner = make_off_policy_learner(config_for(e.alg), kObs, kAct, 2, rng);
    EXPECT_EQ(learner->actor_kind(), e.kind);
    EXPECT_EQ(learner->reward_critic_count(), e.reward_critics);
    EXPECT_EQ(learner->cost_count(), 2);
    EXPECT_EQ(learner->actor().output_size(), e.actor_outputs);
    EXPECT_EQ(learner->temperature() != nullptr, e.temperature);
    EXPECT_DOUBLE_EQ(learner->alpha(), e.temperature ? 0.3 : 0.0);
  }
}

TEST(MakeOffPolicyLearner, RefusesAnOnPolicyAlgorithmNamingIt) {
  Rng rng(1);
  try {
    make_off_policy_learner(config_for(Algorithm::ppo), kObs, kAct, 0, rng);
    FAIL() << "ppo got an off-policy learner";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("ppo is not an off-policy algorithm"), std::string::npos) << e.what();
  }
}

TEST(OffPolicyLearners, ActDrawsTheirExplorationNoiseInActionOrder) {
  const Eigen::VectorXd observation = Eigen::Vector3d(0.2, -0.4, 0.7);
  const std::span<const double> view(observation.data(), 3);
  for (const Algorithm alg : {Algorithm::sac, Algorithm::td3, Algorithm::ddpg}) {
    SCOPED_TRACE(std::string(to_string(alg)));
    RunConfig config = config_for(alg);
    config.off_policy.exploration_noise = 0.4;
    Rng init(2);
    const auto learner = make_off_policy_learner(config, kObs, kAct, 0, init);
    const Eigen::VectorXd outputs = learner->actor().forward(observation);
    Rng unused(0);
    Eigen::VectorXd action(kAct);
    learner->act(view, /*deterministic=*/true, unused, action);
    for (int j = 0; j < kAct; ++j) EXPECT_DOUBLE_EQ(action(j), std::tanh(outputs(j)));
    Rng rng(3), oracle(3);
    learner->act(view, /*deterministic=*/false, rng, action);
    for (int j = 0; j < kAct; ++j) {
      const double eps = standard_normal(oracle);
      const double expected =
          alg == Algorithm::sac
              ? std::tanh(outputs(j) + std::exp(std::clamp(outputs(kAct + j), -20.0, 2.0)) * eps)  // tanh(mu + sigma eps)
              : std::clamp(std::tanh(outputs(j)) + 0.4 * eps, -1.0, 1.0);
      EXPECT_DOUBLE_EQ(action(j), expected);
    }
  }
}

TEST(Td3Learner, TargetsTakeTheTwinMinimumAtTheSmoothedTargetAction) {
  Rng rng(4);
  RunConfig config = config_for(Algorithm::td3_lag);
  config.off_policy.policy_noise = 0.3;
  config.off_policy.noise_clip = 0.4;
  const auto owned = make_off_policy_learner(config, kObs, kAct, 1, rng);
  OffPolicyLearner& learner = *owned;
  perturb_targets(learner, rng);
  const ReplayBatch batch = random_batch(rng, 1);
  const Eigen::MatrixXd noise = random_matrix(kRows, kAct, rng, 3.0);  // some beyond the clip
  learner.compute_targets(batch, noise);
  for (int i = 0; i < kRows; ++i) {
    const Eigen::VectorXd next = batch.next_observations.row(i).transpose();
    const Eigen::VectorXd mu = learner.target_actor().forward(next);
    Eigen::VectorXd action(kAct);
    for (int j = 0; j < kAct; ++j) {
      // a' = clip(tanh(mu'(s')) + clip(sigma eps, -c, c), -1, 1)
      action(j) = std::clamp(std::tanh(mu(j)) + std::clamp(0.3 * noise(i, j), -0.4, 0.4), -1.0, 1.0);
    }
    const Eigen::VectorXd input = critic_input(next, action);
    const double q = std::min(learner.target_reward_critic(0).forward(input)(0),
                              learner.target_reward_critic(1).forward(input)(0));
    const double bootstrap = batch.terminals(i) == 1.0 ? 0.0 : batch.discounts(i);
    EXPECT_NEAR(learner.reward_targets()(i), batch.rewards(i) + bootstrap * q, 1e-12);
    EXPECT_NEAR(learner.cost_targets()(i, 0),
                batch.costs(i, 0) + bootstrap * learner.target_cost_critic(0).forward(input)(0), 1e-12);
  }
}

TEST(Td3Learner, ActorLossUsesTheFirstCriticAloneAndTheRescaledCostTerm) {
  Rng rng(5);
  const auto owned = make_off_policy_learner(config_for(Algorithm::td3_lag), kObs, kAct, 1, rng);
  OffPolicyLearner& learner = *owned;
  const ReplayBatch batch = random_batch(rng, 1);
  const std::vector<double> lambdas{0.8};
  Eigen::VectorXd gradient(learner.actor().num_parameters());
  double log_prob_mean = 1.0;
  const double loss =
      learner.actor_loss(batch, Eigen::MatrixXd::Zero(kRows, kAct), lambdas, gradient, &log_prob_mean);
  // mean [-Q_1(s, tanh(mu(s))) + lambda Q_C(s, tanh(mu(s)))] / (1 + lambda)
  double expected = 0.0;
  for (int i = 0; i < kRows; ++i) {
    const Eigen::VectorXd observation = batch.observations.row(i).transpose();
    const Eigen::VectorXd action = learner.actor().forward(observation).array().tanh();
    const Eigen::VectorXd input = critic_input(observation, action);
    expected += (-learner.reward_critic(0).forward(input)(0) + 0.8 * learner.cost_critic(0).forward(input)(0)) /
                (1.8 * kRows);
  }
  EXPECT_NEAR(loss, expected, 1e-12);
  EXPECT_EQ(log_prob_mean, 0.0);
}

TEST(OffPolicyLearners, DeterministicActorsFillTheCheckpointsTemperatureSlotWithAnUnusedOne) {
  for (const Algorithm alg : {Algorithm::td3, Algorithm::ddpg}) {
    SCOPED_TRACE(std::string(to_string(alg)));
    Rng rng(6);
    RunConfig config = config_for(alg);
    config.off_policy.alpha_init = 0.25;
    const auto learner = make_off_policy_learner(config, kObs, kAct, 0, rng);
    const ReplayBatch batch = random_batch(rng, 0);
    learner->update(batch, {}, rng, MpiContext::single_process());
    BinaryWriter writer;
    learner->save(writer);
    // ... log alpha = log(alpha_init), its Adam never stepped (m = v = (0), t = 0), the update count
    BinaryWriter tail;
    tail.write_f64(std::log(0.25));
    tail.write_vector(Eigen::VectorXd::Zero(1));
    tail.write_vector(Eigen::VectorXd::Zero(1));
    tail.write_i64(0);
    tail.write_i64(1);
    EXPECT_TRUE(writer.bytes().ends_with(tail.bytes()));
    Rng other(7);
    const auto restored = make_off_policy_learner(config, kObs, kAct, 0, other);
    BinaryReader reader(writer.bytes(), "test");
    restored->load(reader);
    reader.expect_end();
    EXPECT_EQ(restored->actor().parameters(), learner->actor().parameters());
    EXPECT_EQ(restored->update_count(), 1);
  }
}

}  // namespace off_policy_learners_test
}  // namespace
}  // namespace bsg::algos
