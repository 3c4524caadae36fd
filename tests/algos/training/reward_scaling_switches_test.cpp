// The reward-scaling switches (docs/algorithms.md#reward-scaling, quirks Q5 and
// Q19) against hand-computed examples: the return statistic's bootstrap in raw
// units, no bootstrap at time-outs, V's output layer scaled by old/new std
// after the statistic's update, and a statistic frozen after its warm-up.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "../../test_support.h"
#include "algos/core/actor_critic.h"
#include "algos/core/buffer.h"
#include "algos/training/rollout.h"
#include "algos/training/on_policy_trainer.h"
#include "algos/core/value_function.h"
#include "common/run_config.h"
#include "../scripted_env.h"

namespace bsg::algos {
namespace {

using testing::ScriptedEnv;
using testing::TemporaryDirectory;

// Rewards (1, 2), gamma 0.5, bootstrap V(s_T) = 3, s_ret + 1e-5 = 2.
Buffer two_step_path(bool consistent_return_statistic) {
  Buffer buffer(2, 1, 1,
                BufferOptions{.gamma = 0.5, .lam = 1.0, .lam_c = 1.0, .consistent_return_statistic = consistent_return_statistic});
  buffer.store(Eigen::VectorXd::Zero(1), Eigen::VectorXd::Zero(1), 1.0, 0.0, 0.0, 0.0, 0.0);
  buffer.store(Eigen::VectorXd::Zero(1), Eigen::VectorXd::Zero(1), 2.0, 0.0, 0.0, 0.0, 0.0);
  buffer.finish_path(3.0, 0.0, 2.0 - Buffer::kStdEpsilon, PathEnd::episode_end);
  return buffer;
}

TEST(RewardScalingSwitches, TheConsistentStatisticEndsTheReturnInRawUnits) {
  // Original (Q5): G_1 = 2 + 0.5 * 3 = 3.5, G_0 = 1 + 0.5 * 3.5 = 2.75.
  const Buffer original = two_step_path(false);
  EXPECT_NEAR(original.discounted_returns()[1], 3.5, 1e-12);
  EXPECT_NEAR(original.discounted_returns()[0], 2.75, 1e-12);
  // Consistent: V(s_T) (s_ret + 1e-5) = 6; G_1 = 2 + 3 = 5, G_0 = 1 + 2.5 = 3.5.
  const Buffer consistent = two_step_path(true);
  EXPECT_NEAR(consistent.discounted_returns()[1], 5.0, 1e-12);
  EXPECT_NEAR(consistent.discounted_returns()[0], 3.5, 1e-12);
  // GAE and V's targets stay in scaled units: A_1 = 2/2 + 0.5 * 3 = 2.5, A_0 = 0.5 + 0.5 * 2.5 = 1.75.
  for (const Buffer* buffer : {&original, &consistent}) {
    EXPECT_NEAR(buffer->advantages()[1], 2.5, 1e-12);
    EXPECT_NEAR(buffer->advantages()[0], 1.75, 1e-12);
  }
}

TEST(RewardScalingSwitches, WithoutTimeoutBootstrapATimeOutEndsTheReturn) {
  RunConfig config;
  config.hidden_sizes = {8, 8};
  Rng init_rng(1);
  const ActorCritic actor_critic(3, 2, config, init_rng);
  // 500 steps = two episodes of 250: the time-out at t = 249 and the one at the
  // epoch's last step t = 499, both without bootstrap: A_t = r~_t - V_t.
  for (const int t : {249, 499}) {
    Buffer buffer(500, 3, 2);
    RolloutCollector collector(3, 2, RolloutOptions{500, 250, true, false});
    ScriptedEnv env(250);
    Rng noise(2);
    collector.collect(env, 7, actor_critic, noise, buffer);
    const double scale = actor_critic.return_normalizer.std()[0] + Buffer::kStdEpsilon;
    EXPECT_NEAR(buffer.advantages()[t], buffer.rewards()[t] / scale - buffer.values()[t], 1e-12) << t;
    EXPECT_NEAR(buffer.cost_advantages()[t], buffer.costs()[t] - buffer.cost_values()[t], 1e-12) << t;
    // G_t of the last step is its raw reward alone.
    EXPECT_EQ(buffer.discounted_returns()[t], buffer.rewards()[t]) << t;
  }
}

TEST(RewardScalingSwitches, ScaleOutputMultipliesEveryPredictionByTheFactor) {
  // A 1-1-1 net with weights and biases set by hand: V(x) = 2 tanh(0.5 x + 0.2) + 1.
  Rng rng(3);
  ValueFunction value(1, {1}, rng);
  Eigen::VectorXd parameters(4);
  parameters << 0.5, 0.2, 2.0, 1.0;  // layer 0 weight, bias; layer 1 weight, bias
  value.net().set_parameters(parameters);
  MlpSampleWorkspace workspace;
  const Eigen::VectorXd x = Eigen::VectorXd::Constant(1, 1.0);
  const double v = 2.0 * std::tanh(0.7) + 1.0;  // 2.2087355...
  EXPECT_NEAR(value.predict(x, workspace), v, 1e-12);
  value.scale_output(3.0);
  EXPECT_NEAR(value.predict(x, workspace), 3.0 * v, 1e-12);
  EXPECT_EQ(value.net().parameters()[0], 0.5);  // the hidden layer is untouched
  EXPECT_EQ(value.net().parameters()[1], 0.2);
  EXPECT_THROW(value.scale_output(0.0), std::invalid_argument);
  EXPECT_THROW(value.scale_output(std::nan("")), std::invalid_argument);
}

RunConfig scripted_trpo(int epochs) {
  RunConfig config;
  config.env_id = "Scripted-v0";
  config.alg = Algorithm::trpo;
  config.hidden_sizes = {16, 16};
  config.epochs = epochs;
  config.steps_per_epoch = 400;  // 4 episodes of 100 steps
  config.max_ep_len = 100;
  config.eval_episodes = 0;
  return config;
}

const ActorCritic& trained(OnPolicyTrainer& trainer) {
  trainer.run();
  return trainer.actor_critic();
}

TEST(RewardScalingSwitches, Q19ScalesVsOutputLayerByOldOverNewStdAndNothingElse) {
  TemporaryDirectory dir;
  RunConfig config = scripted_trpo(1);
  OnPolicyTrainer plain(config, RunDirectory(dir.path() / "plain"), MpiContext::single_process(), {},
                        std::make_unique<ScriptedEnv>(100));
  config.rescale_value_output = true;
  OnPolicyTrainer rescaled(config, RunDirectory(dir.path() / "rescaled"), MpiContext::single_process(), {},
                           std::make_unique<ScriptedEnv>(100));
  const ActorCritic& a = trained(plain);
  const ActorCritic& b = trained(rescaled);
  // The statistic starts at std 1 and is the same in both runs after epoch 0.
  const double new_std = a.return_normalizer.std()[0];
  ASSERT_EQ(new_std, b.return_normalizer.std()[0]);
  ASSERT_GT(std::abs(new_std - 1.0), 0.1);
  const double factor = (1.0 + Buffer::kStdEpsilon) / (new_std + Buffer::kStdEpsilon);
  const Mlp& va = a.value.net();
  const Mlp& vb = b.value.net();
  const int last = va.num_layers() - 1;
  const Eigen::Index output_start = va.weight_offset(last);
  EXPECT_EQ(vb.parameters().head(output_start), va.parameters().head(output_start));
  const Eigen::VectorXd expected = va.parameters().tail(va.num_parameters() - output_start) * factor;
  EXPECT_TRUE(vb.parameters().tail(vb.num_parameters() - output_start).isApprox(expected, 1e-14));
  EXPECT_EQ(b.policy.mean_net().parameters(), a.policy.mean_net().parameters());
}

TEST(RewardScalingSwitches, TheStatisticIsFrozenAfterItsWarmUpEpochs) {
  TemporaryDirectory dir;
  RunConfig config = scripted_trpo(4);
  config.reward_scale_warmup_epochs = 2;
  OnPolicyTrainer trainer(config, RunDirectory(dir.path() / "run"), MpiContext::single_process(), {},
                          std::make_unique<ScriptedEnv>(100));
  // Updated in epochs 0 and 1 only: 2 x 400 returns.
  EXPECT_EQ(trained(trainer).return_normalizer.count(), 800.0);
}

}  // namespace
}  // namespace bsg::algos
