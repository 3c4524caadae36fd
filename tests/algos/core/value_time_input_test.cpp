// The time input of the value nets (`value_time_input`, docs/algorithms.md#value-time-input)
// against hand-computed examples: each step's place in its episode, the input
// (T - t)/T that V and V_C see in the rollout and at the bootstrap, and a
// trainer that fits, saves and resumes nets with the extra input.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "../../test_support.h"
#include "algos/core/actor_critic.h"
#include "algos/core/buffer.h"
#include "algos/training/rollout.h"
#include "algos/training/on_policy_trainer.h"
#include "common/run_config.h"
#include "../scripted_env.h"

namespace bsg::algos {
namespace {

using testing::ScriptedEnv;
using testing::TemporaryDirectory;

RunConfig time_input_config(int max_ep_len) {
  RunConfig config;
  config.hidden_sizes = {1};
  config.max_ep_len = max_ep_len;
  config.value_time_input = true;
  return config;
}

// V(x) = tanh(x_last): a 4-1-1 net whose only non-zero weights read the time
// input (row-major 1 x 4 first layer, then bias 0, output weight 1, bias 0).
void read_only_the_time_input(ValueFunction& value) {
  Eigen::VectorXd parameters(7);
  parameters << 0.0, 0.0, 0.0, 1.0, 0.0, 1.0, 0.0;
  value.net().set_parameters(parameters);
}

TEST(ValueTimeInput, TheBufferRecordsEachStepsPlaceInItsEpisode) {
  RunConfig config = time_input_config(4);
  Rng init_rng(1);
  const ActorCritic actor_critic(3, 2, config, init_rng);
  Rng noise(2);
  {
    // Time-outs after 4 steps, then the epoch cut after 2 steps of the third episode.
    Buffer buffer(10, 3, 2);
    RolloutCollector collector(3, 2, RolloutOptions{10, 4, true, true});
    ScriptedEnv env(100);
    collector.collect(env, 7, actor_critic, noise, buffer);
    Eigen::VectorXi expected(10);
    expected << 0, 1, 2, 3, 0, 1, 2, 3, 0, 1;
    EXPECT_EQ(buffer.episode_steps(), expected);
  }
  {
    // Terminals after 3 steps.
    Buffer buffer(7, 3, 2);
    RolloutCollector collector(3, 2, RolloutOptions{7, 4, true, true});
    ScriptedEnv env(100, 3);
    collector.collect(env, 7, actor_critic, noise, buffer);
    Eigen::VectorXi expected(7);
    expected << 0, 1, 2, 0, 1, 2, 0;
    EXPECT_EQ(buffer.episode_steps(), expected);
  }
}

TEST(ValueTimeInput, TheValueNetsHaveOneMoreInputOnlyWithTheSwitch) {
  RunConfig config;
  config.hidden_sizes = {8};
  config.constraints = {ConstraintConfig{}, ConstraintConfig{}};
  Rng rng_a(1);
  const ActorCritic plain(3, 2, config, rng_a);
  EXPECT_EQ(plain.value_input_size(), 3);
  EXPECT_EQ(plain.value.net().input_size(), 3);
  config.value_time_input = true;
  Rng rng_b(1);
  const ActorCritic timed(3, 2, config, rng_b);
  EXPECT_EQ(timed.value_input_size(), 4);
  EXPECT_EQ(timed.policy.mean_net().input_size(), 3);  // the policy does not see the time
  EXPECT_EQ(timed.value.net().input_size(), 4);
  EXPECT_EQ(timed.cost_value.net().input_size(), 4);
  EXPECT_EQ(timed.cost_value_net(1).net().input_size(), 4);
}

TEST(ValueTimeInput, TheBatchInputAppendsTheFractionOfTheTimeLimitLeft) {
  Rng init_rng(1);
  const ActorCritic actor_critic(2, 1, time_input_config(4), init_rng);
  Eigen::MatrixXd normalized(3, 2);
  normalized << 1, 2, 3, 4, 5, 6;
  Eigen::VectorXi steps(3);
  steps << 0, 3, 4;
  Eigen::MatrixXd inputs(3, 3);
  actor_critic.value_inputs(normalized, steps, inputs);
  Eigen::MatrixXd expected(3, 3);
  expected << 1, 2, 1.0, 3, 4, 0.25, 5, 6, 0.0;
  EXPECT_EQ(inputs, expected);
}

TEST(ValueTimeInput, TheRolloutAndItsBootstrapsSeeTheTimeLeft) {
  Rng init_rng(1);
  ActorCritic actor_critic(3, 2, time_input_config(4), init_rng);
  read_only_the_time_input(actor_critic.value);
  read_only_the_time_input(actor_critic.cost_value);
  Buffer buffer(10, 3, 2);
  RolloutCollector collector(3, 2, RolloutOptions{10, 4, true, true});
  ScriptedEnv env(100);
  Rng noise(2);
  collector.collect(env, 7, actor_critic, noise, buffer);
  // Step t of its episode sees (4 - t)/4: V_t = tanh(1), tanh(0.75), tanh(0.5), tanh(0.25), ...
  const double by_step[4] = {std::tanh(1.0), std::tanh(0.75), std::tanh(0.5), std::tanh(0.25)};
  for (int t = 0; t < 10; ++t) {
    EXPECT_NEAR(buffer.values()[t], by_step[t % 4], 1e-15) << t;
    EXPECT_NEAR(buffer.cost_values()[t], by_step[t % 4], 1e-15) << t;
  }
  const double scale = actor_critic.return_normalizer.std()[0] + Buffer::kStdEpsilon;
  const double gamma = buffer.options().gamma;
  // The time-out at t = 3 bootstraps with V(o_4, 0) = tanh(0) = 0.
  EXPECT_NEAR(buffer.advantages()[3], buffer.rewards()[3] / scale - std::tanh(0.25), 1e-12);
  EXPECT_NEAR(buffer.cost_advantages()[3], buffer.costs()[3] - std::tanh(0.25), 1e-12);
  // The epoch cut at t = 9 (step 1) bootstraps with step 2's input, 0.5.
  EXPECT_NEAR(buffer.advantages()[9], buffer.rewards()[9] / scale + gamma * std::tanh(0.5) - std::tanh(0.75), 1e-12);
  EXPECT_NEAR(buffer.cost_advantages()[9], buffer.costs()[9] + gamma * std::tanh(0.5) - std::tanh(0.75), 1e-12);
}

TEST(ValueTimeInput, ATrainerFitsSavesAndResumesTheNetsWithTheTimeInput) {
  TemporaryDirectory dir;
  RunConfig config;
  config.env_id = "Scripted-v0";
  config.alg = Algorithm::lag_trpo;  // V_C is fitted too
  config.hidden_sizes = {16, 16};
  config.epochs = 3;
  config.steps_per_epoch = 400;
  config.max_ep_len = 100;
  config.eval_episodes = 0;
  config.value_time_input = true;
  OnPolicyTrainer whole(config, RunDirectory(dir.path() / "whole"), MpiContext::single_process(), {},
                        std::make_unique<ScriptedEnv>(100));
  whole.run();
  TrainerOptions stop;
  stop.stop_after_epochs = 1;
  {
    OnPolicyTrainer first(config, RunDirectory(dir.path() / "split"), MpiContext::single_process(), stop,
                          std::make_unique<ScriptedEnv>(100));
    first.run();
  }
  TrainerOptions resume;
  resume.resume = true;
  OnPolicyTrainer second(config, RunDirectory(dir.path() / "split"), MpiContext::single_process(), resume,
                         std::make_unique<ScriptedEnv>(100));
  second.run();
  const ActorCritic& a = whole.actor_critic();
  const ActorCritic& b = second.actor_critic();
  EXPECT_EQ(a.value.net().input_size(), 4);
  EXPECT_EQ(b.value.net().parameters(), a.value.net().parameters());
  EXPECT_EQ(b.cost_value.net().parameters(), a.cost_value.net().parameters());
  EXPECT_EQ(b.policy.mean_net().parameters(), a.policy.mean_net().parameters());
}

}  // namespace
}  // namespace bsg::algos
