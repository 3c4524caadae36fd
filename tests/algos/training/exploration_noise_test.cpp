// The exploration noise of each epoch with a floor (exploration_std_floor) and the
// sampled evaluation (sampled_evaluation), against hand-computed values:
// sigma_k = max(0.499 (1 - k/E) + 0.01, floor), and sampled actions a = mu + sigma eps
// with mu = 0 (a mean net of zeros) and eps drawn from the evaluation's own stream.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "../../test_support.h"
#include "algos/training/evaluation.h"
#include "algos/training/evaluation_files.h"
#include "algos/training/exploration_noise.h"
#include "algos/core/actor_critic_acting.h"
#include "algos/training/on_policy_trainer.h"
#include "common/random.h"
#include "common/seeding.h"
#include "../scripted_env.h"
#include "../scripted_training.h"

using bsg::testing::read_text_file;
using bsg::testing::ScriptedEnv;
using bsg::testing::TemporaryDirectory;
using bsg::testing::scripted_config;
using bsg::testing::sigma_of_each_epoch;

namespace {

bsg::RunConfig config_of(int epochs, double floor) {
  bsg::RunConfig config;
  config.epochs = epochs;
  config.exploration_std_floor = floor;
  return config;
}

// A scripted environment that keeps every action it is given.
class ActionRecordingEnv : public ScriptedEnv {
 public:
  using ScriptedEnv::ScriptedEnv;
  bsg::envs::StepResult step(std::span<const double> action) override {
    actions.insert(actions.end(), action.begin(), action.end());
    return ScriptedEnv::step(action);
  }
  std::vector<double> actions;
};

}  // namespace

TEST(ExplorationStd, TheFloorHoldsSigmaOnceTheScheduleFallsBelowIt) {
  const bsg::RunConfig c = config_of(100, 0.1);
  EXPECT_NEAR(bsg::algos::exploration_std(c, 0), 0.509, 1e-15);
  EXPECT_NEAR(bsg::algos::exploration_std(c, 50), 0.2595, 1e-15);
  EXPECT_NEAR(bsg::algos::exploration_std(c, 80), 0.1098, 1e-15);  // 0.499 * 0.2 + 0.01, above the floor
  EXPECT_EQ(bsg::algos::exploration_std(c, 90), 0.1);              // 0.0599 < 0.1
  EXPECT_EQ(bsg::algos::exploration_std(c, 99), 0.1);
  EXPECT_THROW(bsg::algos::exploration_std(c, 100), std::invalid_argument);
  EXPECT_THROW(bsg::algos::exploration_std(c, -1), std::invalid_argument);
}

TEST(ExplorationStd, WithoutAFloorItIsTheScheduleBitForBit) {
  bsg::RunConfig c = config_of(100, 0.0);
  for (int k = 0; k < 100; ++k) EXPECT_EQ(bsg::algos::exploration_std(c, k), bsg::algos::GaussianPolicy::annealed_std(k, 100)) << k;
  c.exploration_anneal_epochs = 80;
  for (int k = 0; k < 100; ++k) {
    EXPECT_EQ(bsg::algos::exploration_std(c, k), bsg::algos::GaussianPolicy::annealed_std(k, 100, 80)) << k;
  }
  c.use_exploration_noise_anneal = false;
  c.exploration_anneal_epochs = 0;
  EXPECT_EQ(bsg::algos::exploration_std(c, 37), 0.5);
}

TEST(ExplorationStd, AFloorAfterAnEarlyEndOfTheAnnealingHoldsTheFloor) {
  bsg::RunConfig c = config_of(100, 0.05);
  c.exploration_anneal_epochs = 80;
  EXPECT_NEAR(bsg::algos::exploration_std(c, 40), 0.2595, 1e-15);
  EXPECT_EQ(bsg::algos::exploration_std(c, 80), 0.05);  // the schedule alone would hold 0.01
  EXPECT_EQ(bsg::algos::exploration_std(c, 99), 0.05);
}

TEST(ExplorationStd, TheLastEpochsSigmaIsSetForTheSampledEvaluation) {
  const bsg::RunConfig c = config_of(100, 0.0);
  bsg::Rng rng(1);
  bsg::algos::GaussianPolicy policy(3, 2, {4}, rng);
  bsg::algos::set_last_epoch_std(c, 100, policy);
  EXPECT_NEAR(policy.std(), 0.499 * 0.01 + 0.01, 1e-15);  // epoch 99 of 100
  bsg::algos::set_last_epoch_std(c, 0, policy);
  EXPECT_NEAR(policy.std(), 0.509, 1e-15);
  bsg::algos::set_last_epoch_std(config_of(100, 0.2), 100, policy);
  EXPECT_EQ(policy.std(), 0.2);
}

TEST(Trainer, ASigmaFloorHoldsTheNoiseOfTheLastEpochs) {
  // E = 5, floor 0.2: 0.499 (1 - k/5) + 0.01 = 0.509, 0.4092, 0.3094, 0.2096, then 0.1098 -> 0.2.
  bsg::RunConfig config = scripted_config();
  config.exploration_std_floor = 0.2;
  config.eval_episodes = 0;
  const std::vector<double> sigmas = sigma_of_each_epoch(config);
  ASSERT_EQ(sigmas.size(), 5u);
  const double expected[5] = {0.509, 0.4092, 0.3094, 0.2096, 0.2};
  for (int k = 0; k < 5; ++k) EXPECT_NEAR(sigmas[static_cast<std::size_t>(k)], expected[k], 1e-15) << k;
}

TEST(SampledEvaluation, ActionsAreSigmaTimesTheEvaluationStreamsNormalsAroundAZeroMean) {
  bsg::RunConfig config = scripted_config();
  bsg::Rng init(3);
  bsg::algos::ActorCritic ac(3, 2, config, init);
  ac.policy.mean_net().set_parameters(Eigen::VectorXd::Zero(ac.policy.mean_net().num_parameters()));  // mu = 0
  ac.policy.set_std(0.3);
  const std::int64_t seed = 11;

  bsg::algos::ActorCriticActing acting(ac);
  ActionRecordingEnv mean_env(100);
  const bsg::algos::EvaluationSummary mean =
      bsg::algos::evaluate_policy(mean_env, acting, 2, seed, 100, bsg::MpiContext::single_process());
  ASSERT_EQ(mean_env.actions.size(), 400u);  // 2 episodes x 100 steps x 2 dimensions
  for (double a : mean_env.actions) ASSERT_EQ(a, 0.0);
  EXPECT_EQ(mean.action_std, 0.0);
  EXPECT_EQ(bsg::algos::evaluation_json(mean, false).find("action_std"), std::string::npos);

  ActionRecordingEnv sampled_env(100);
  bsg::algos::EvaluationSummary sampled = bsg::algos::evaluate_policy(sampled_env, acting, 2, seed, 100,
                                                                        bsg::MpiContext::single_process(), {}, {},
                                                                        bsg::algos::EvaluationActions::sampled);
  ASSERT_EQ(sampled_env.actions.size(), 400u);
  bsg::Rng expected_noise(bsg::derive_seed(static_cast<std::uint64_t>(seed), bsg::SeedStream::evaluation_action_noise, 0));
  double sum_of_squares = 0.0;
  for (std::size_t i = 0; i < sampled_env.actions.size(); ++i) {
    ASSERT_NEAR(sampled_env.actions[i], 0.3 * bsg::standard_normal(expected_noise), 1e-12) << i;
    sum_of_squares += sampled_env.actions[i] * sampled_env.actions[i];
  }
  // 400 draws of N(0, 0.3^2): the sample RMS lies within 0.3 (1 +- 0.15) with overwhelming probability.
  EXPECT_NEAR(std::sqrt(sum_of_squares / 400.0), 0.3, 0.045);
  EXPECT_EQ(sampled.action_std, 0.0);  // the acting policy's sigma is the caller's to report (on_policy_family.cpp)
  sampled.action_std = ac.policy.std();
  EXPECT_NE(bsg::algos::evaluation_json(sampled, false).find("\"action_std\": 0.3"), std::string::npos)
      << bsg::algos::evaluation_json(sampled, false);
  // The scripted reward ignores actions, so J is the same either way; the environment stream too.
  EXPECT_EQ(sampled.mean_return, mean.mean_return);
  EXPECT_EQ(sampled_env.seeded_resets, mean_env.seeded_resets);
}

TEST(SampledEvaluation, TheTrainerSamplesAtTheLastEpochsSigma) {
  TemporaryDirectory dir;
  bsg::RunConfig config = scripted_config();
  config.sampled_evaluation = true;
  bsg::algos::OnPolicyTrainer trainer(config, bsg::algos::RunDirectory(dir.path() / "run"), bsg::MpiContext::single_process(), {},
                               std::make_unique<ScriptedEnv>(100));
  const bsg::algos::TrainingOutcome outcome = trainer.run();
  ASSERT_TRUE(outcome.evaluation.has_value());
  EXPECT_NEAR(outcome.evaluation->action_std, 0.499 * 0.2 + 0.01, 1e-15);  // epoch 4 of 5
  const std::string json = read_text_file(dir.path() / "run" / "evaluation.json");
  const std::size_t at = json.find("\"action_std\": ");
  ASSERT_NE(at, std::string::npos) << json;
  EXPECT_NEAR(std::stod(json.substr(at + 14)), 0.1098, 1e-15) << json;
}
