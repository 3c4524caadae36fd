// Rollout bookkeeping (docs/algorithms.md#rollout, #test-oracles) on a scripted environment:
// episodes per epoch, epoch cuts, terminals, bootstrap values, seeding.
#include <gtest/gtest.h>

#include <cmath>

#include "algos/core/actor_critic.h"
#include "algos/core/buffer.h"
#include "algos/training/epoch_log.h"
#include "algos/training/rollout.h"
#include "common/run_config.h"
#include "../scripted_env.h"

namespace {

using bsg::testing::ScriptedEnv;

struct Fixture {
  explicit Fixture(int local_steps, int max_ep_len = 250)
      : actor_critic(3, 2, small_config(), init_rng),
        buffer(local_steps, 3, 2),
        collector(3, 2, bsg::algos::RolloutOptions{local_steps, max_ep_len, true}) {}

  static bsg::RunConfig small_config() {
    bsg::RunConfig config;
    config.hidden_sizes = {8, 8};
    return config;
  }

  bsg::Rng init_rng{1};
  bsg::algos::ActorCritic actor_critic;
  bsg::algos::Buffer buffer;
  bsg::algos::RolloutCollector collector;
  bsg::Rng noise{2};
};

}  // namespace

TEST(Rollout, EpisodesPerEpochAreNOverMaxEpLenWithoutEarlyTerminations) {
  Fixture f(1000);
  ScriptedEnv env(250);
  f.collector.collect(env, 7, f.actor_critic, f.noise, f.buffer);
  ASSERT_EQ(f.buffer.episodes().size(), 4u);  // N / max_ep_len
  const double expected_return = 250 * 1.0 + 0.01 * 250 * 251 / 2;  // sum of 1 + 0.01 t
  for (const bsg::algos::EpisodeStats& e : f.buffer.episodes()) {
    EXPECT_EQ(e.episode_length, 250);
    EXPECT_NEAR(e.episode_return, expected_return, 1e-9);
    EXPECT_EQ(e.episode_cost, 25.0);  // every 10th step
  }
  EXPECT_TRUE(f.buffer.full());
}

TEST(Rollout, ConfiguredMaxEpLenCutsEpisodesBeforeTheEnvironmentDoes) {
  Fixture f(1000, 100);
  ScriptedEnv env(250);
  f.collector.collect(env, 7, f.actor_critic, f.noise, f.buffer);
  ASSERT_EQ(f.buffer.episodes().size(), 10u);
  for (const bsg::algos::EpisodeStats& e : f.buffer.episodes()) EXPECT_EQ(e.episode_length, 100);
}

TEST(Rollout, AnEpisodeCutAtTheEpochEndContributesDataButNoStatistics) {
  Fixture f(1100);
  ScriptedEnv env(250);
  f.collector.collect(env, 7, f.actor_critic, f.noise, f.buffer);
  EXPECT_EQ(f.buffer.episodes().size(), 4u);  // the last 100 steps are a cut path
  EXPECT_EQ(f.buffer.size(), 1100);
  EXPECT_EQ(env.total_steps, 1100);
  // The cut path has finished GAE: targets are filled and finite.
  EXPECT_TRUE(f.buffer.value_targets().tail(100).allFinite());
  EXPECT_NE(f.buffer.advantages()[1099], 0.0);
}

TEST(Rollout, EarlyTerminationsGiveShorterEpisodesAndNoBootstrap) {
  Fixture f(1000);
  ScriptedEnv env(250, /*terminate_after=*/100);
  f.collector.collect(env, 7, f.actor_critic, f.noise, f.buffer);
  ASSERT_EQ(f.buffer.episodes().size(), 10u);
  // True terminal at t = 99 (not the epoch's last step): A_t = r~_t - V_t, no bootstrap.
  const double reward_scale = f.actor_critic.return_normalizer.std()[0] + bsg::algos::Buffer::kStdEpsilon;
  const double scaled_reward = f.buffer.rewards()[99] / reward_scale;
  EXPECT_NEAR(f.buffer.advantages()[99], scaled_reward - f.buffer.values()[99], 1e-12);
  EXPECT_NEAR(f.buffer.cost_advantages()[99], f.buffer.costs()[99] - f.buffer.cost_values()[99], 1e-12);
}

TEST(Rollout, TimeOutsBootstrapWithTheValueOfTheNextObservation) {
  Fixture f(500);
  ScriptedEnv env(250);
  f.collector.collect(env, 7, f.actor_critic, f.noise, f.buffer);
  // Time-out at t = 249: A_t = r~_t + gamma V(o_250) - V_t, with o_250 the
  // observation after the last step (episode step 250, offset 7).
  Eigen::VectorXd next(3);
  next << 25.0, 7.0, 1.0;
  Eigen::VectorXd normalized(3);
  f.actor_critic.normalize_observation(next, normalized);
  bsg::MlpSampleWorkspace workspace;
  const double v_next = f.actor_critic.value.predict(normalized, workspace);
  const double reward_scale = f.actor_critic.return_normalizer.std()[0] + bsg::algos::Buffer::kStdEpsilon;
  const double gamma = f.buffer.options().gamma;
  EXPECT_NEAR(f.buffer.advantages()[249],
              f.buffer.rewards()[249] / reward_scale + gamma * v_next - f.buffer.values()[249], 1e-12);
}

TEST(Rollout, TheEnvironmentIsSeededOncePerEpochAndNotResetAfterTheCut) {
  Fixture f(1000);
  ScriptedEnv env(250);
  f.collector.collect(env, 1234, f.actor_critic, f.noise, f.buffer);
  ASSERT_EQ(env.seeded_resets.size(), 1u);
  EXPECT_EQ(env.seeded_resets[0], 1234u);
  EXPECT_EQ(env.unseeded_resets, 3);  // after episodes 1-3; not after the epoch end
  f.collector.collect(env, 99, f.actor_critic, f.noise, f.buffer);
  ASSERT_EQ(env.seeded_resets.size(), 2u);
  EXPECT_EQ(env.seeded_resets[1], 99u);
}

TEST(Rollout, SameSeedsGiveTheSameData) {
  Fixture a(600);
  Fixture b(600);
  ScriptedEnv env_a(250);
  ScriptedEnv env_b(250);
  a.collector.collect(env_a, 5, a.actor_critic, a.noise, a.buffer);
  b.collector.collect(env_b, 5, b.actor_critic, b.noise, b.buffer);
  EXPECT_EQ(a.buffer.actions(), b.buffer.actions());
  EXPECT_EQ(a.buffer.advantages(), b.buffer.advantages());
}

TEST(Rollout, LogProbabilitiesMatchThePolicyAtTheStoredActions) {
  Fixture f(300);
  ScriptedEnv env(100);
  f.actor_critic.policy.set_std(0.3);
  f.collector.collect(env, 5, f.actor_critic, f.noise, f.buffer);
  Eigen::MatrixXd normalized(300, 3);
  f.actor_critic.normalize_observations(f.buffer.observations(), normalized);
  // The rollout's one-sample passes are double whatever the dtype; so is the oracle.
  bsg::Mlp mean_net = f.actor_critic.policy.mean_net();
  mean_net.set_dtype(bsg::Dtype::float64);
  bsg::MlpBatchWorkspace workspace;
  const Eigen::MatrixXd means = mean_net.forward_batch(normalized, workspace);
  Eigen::VectorXd log_probs(300);
  f.actor_critic.policy.log_prob_batch(means, f.buffer.actions(), log_probs);
  EXPECT_LT((log_probs - f.buffer.log_probs()).cwiseAbs().maxCoeff(), 1e-10);
}

TEST(EpisodeStatistics, PooledOverOneRankAreTheBufferEpisodes) {
  Fixture f(1000);
  ScriptedEnv env(250, 100);
  f.collector.collect(env, 7, f.actor_critic, f.noise, f.buffer);
  const bsg::algos::EpisodeStatistics stats =
      bsg::algos::pool_episode_statistics(f.buffer, bsg::MpiContext::single_process());
  EXPECT_EQ(stats.episode_length.count, 10);
  EXPECT_EQ(stats.episode_length.mean, 100.0);
  EXPECT_EQ(stats.episode_cost.mean, 10.0);
  EXPECT_EQ(stats.episode_cost.std, 0.0);
}
