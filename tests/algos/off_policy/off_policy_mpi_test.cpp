// The off-policy updates under `mpirun -np 2` (docs/algorithms.md#the-off-policy-loop): two ranks
// holding halves of a batch take the gradient steps one process takes on the whole batch (every
// loss is a mean over the batch, so the rank average of the halves' gradients is the whole's), and
// a whole off-policy run on two ranks ends with the same parameters on both.
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "../../test_support.h"
#include "../scripted_env.h"
#include "algos/off_policy/make_off_policy_learner.h"
#include "algos/off_policy/off_policy_learner.h"
#include "algos/training/off_policy_trainer.h"
#include "common/mpi_context.h"

namespace bsg::algos {
namespace {

ReplayBatch rows_of(const ReplayBatch& batch, Eigen::Index first, Eigen::Index count) {
  ReplayBatch part;
  part.observations = batch.observations.middleRows(first, count);
  part.actions = batch.actions.middleRows(first, count);
  part.rewards = batch.rewards.segment(first, count);
  part.costs = batch.costs.middleRows(first, count);
  part.next_observations = batch.next_observations.middleRows(first, count);
  part.discounts = batch.discounts.segment(first, count);
  part.terminals = batch.terminals.segment(first, count);
  return part;
}

ReplayBatch random_batch(Eigen::Index rows, Rng& rng) {
  const auto random = [&](Eigen::Index r, Eigen::Index c) {
    Eigen::MatrixXd m(r, c);
    for (Eigen::Index i = 0; i < m.size(); ++i) m.data()[i] = uniform(rng, -1.0, 1.0);
    return m;
  };
  ReplayBatch batch;
  batch.observations = random(rows, 4);
  batch.actions = random(rows, 2);
  batch.rewards = random(rows, 1);
  batch.costs = random(rows, 1).cwiseAbs();
  batch.next_observations = random(rows, 4);
  batch.discounts = Eigen::VectorXd::Constant(rows, 0.95);
  batch.terminals = Eigen::VectorXd::Zero(rows);
  batch.terminals(3) = 1.0;
  batch.terminals(rows - 2) = 1.0;
  return batch;
}

TEST(OffPolicyMpi, TwoRanksWithHalvesTakeTheStepsOfOneProcessOnTheWholeBatch) {
  const MpiContext mpi = MpiContext::world();
  ASSERT_EQ(mpi.size(), 2);
  // DDPG's and (without smoothing noise) TD3's steps draw no random numbers, so both sides see the same data.
  for (const Algorithm alg : {Algorithm::ddpg_lag, Algorithm::td3_lag}) {
    SCOPED_TRACE(std::string(to_string(alg)));
    RunConfig config;
    config.alg = alg;
    config.hidden_sizes = {8, 8};
    config.dtype = Dtype::float64;
    config.off_policy.policy_noise = 0.0;
    config.off_policy.policy_delay = 2;
    Rng init_a(3), init_b(3), data(4);
    const auto owned_whole = make_off_policy_learner(config, 4, 2, 1, init_a);
    const auto owned_half = make_off_policy_learner(config, 4, 2, 1, init_b);
    OffPolicyLearner& whole = *owned_whole;
    OffPolicyLearner& half = *owned_half;
    const ReplayBatch batch = random_batch(32, data);  // the same on both ranks
    const ReplayBatch mine = rows_of(batch, 16 * mpi.rank(), 16);
    const std::vector<double> lambdas{0.7};
    Rng rng_whole(5), rng_half(5);
    for (int step = 0; step < 4; ++step) {
      whole.update(batch, lambdas, rng_whole, MpiContext::single_process());
      half.update(mine, lambdas, rng_half, mpi);
    }
    const auto close = [](const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
      return (a - b).norm() <= 1e-12 * std::max(1.0, b.norm());
    };
    EXPECT_TRUE(close(half.actor().parameters(), whole.actor().parameters()));
    EXPECT_TRUE(close(half.reward_critic(0).parameters(), whole.reward_critic(0).parameters()));
    EXPECT_TRUE(close(half.cost_critic(0).parameters(), whole.cost_critic(0).parameters()));
    EXPECT_TRUE(close(half.target_actor().parameters(), whole.target_actor().parameters()));
  }
}

TEST(OffPolicyMpi, ARunOnTwoRanksKeepsTheirParametersEqual) {
  const MpiContext mpi = MpiContext::world();
  // Each rank its own scripted environments and buffer; the directory is rank 0's, shared.
  std::filesystem::path root;
  std::optional<testing::TemporaryDirectory> directory;
  if (mpi.is_root()) {
    directory.emplace();
    root = directory->path() / "run";
  }
  std::string text = root.string();
  // every rank needs the same path: send rank 0's, character by character, as doubles
  Eigen::VectorXd length = Eigen::VectorXd::Constant(1, static_cast<double>(text.size()));
  mpi.broadcast_from_root(length);
  Eigen::VectorXd characters(static_cast<Eigen::Index>(length(0)));
  for (Eigen::Index i = 0; i < characters.size(); ++i) {
    characters(i) = mpi.is_root() ? static_cast<unsigned char>(text[static_cast<std::size_t>(i)]) : 0.0;
  }
  mpi.broadcast_from_root(characters);
  text.assign(static_cast<std::size_t>(characters.size()), ' ');
  for (Eigen::Index i = 0; i < characters.size(); ++i) text[static_cast<std::size_t>(i)] = static_cast<char>(characters(i));
  RunConfig config;
  config.env_id = "Scripted-v0";
  config.alg = Algorithm::sac_lag;
  config.hidden_sizes = {8, 8};
  config.epochs = 3;
  config.steps_per_epoch = 160;
  config.max_ep_len = 40;
  config.eval_episodes = 2;
  config.cost_limit = 1;
  config.off_policy.start_steps = 40;
  config.off_policy.update_every = 8;
  config.off_policy.batch_size = 16;
  config.off_policy.buffer_size = 100;
  config.off_policy.auto_alpha = true;
  // The multiplier steps in every round on the window pooled over both ranks (a collective).
  config.off_policy.multiplier_schedule = MultiplierSchedule::update_round;
  config.off_policy.multiplier_window = 2;
  std::vector<std::unique_ptr<envs::Env>> envs;
  envs.push_back(std::make_unique<testing::ScriptedEnv>(40, std::nullopt, 3));
  OffPolicyTrainer trainer(config, RunDirectory(text), mpi, {}, std::move(envs));
  ASSERT_TRUE(trainer.run().finished);
  const double sum = trainer.learner().actor().parameters().sum();
  EXPECT_EQ(mpi.min(sum), mpi.max(sum));
  // each rank kept its own buffer: 80 steps per rank and epoch
  EXPECT_EQ(trainer.buffer().total_added(), 3 * 80);
  if (mpi.is_root()) {
    EXPECT_TRUE(std::filesystem::exists(std::filesystem::path(text) / "replay_buffer.r0.log"));
    EXPECT_TRUE(std::filesystem::exists(std::filesystem::path(text) / "replay_buffer.r1.log"));
    EXPECT_TRUE(std::filesystem::exists(std::filesystem::path(text) / "evaluation.json"));
  }
  mpi.sum(0.0);  // rank 0 removes the directory only after every rank is done with it
}

}  // namespace
}  // namespace bsg::algos
