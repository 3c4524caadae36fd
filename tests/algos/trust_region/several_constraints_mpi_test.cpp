// Several constraints under `mpirun -np 2` (docs/algorithms.md#several-constraints, #across-mpi-ranks):
// the per-constraint gradients and episode costs of a batch split over two
// ranks equal those of the whole batch on one rank, and a two-constraint run
// ends with identical parameters and multipliers on both ranks.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "../algorithm_test_support.h"
#include "algos/training/epoch_log.h"
#include "algos/trust_region/trust_region_steps.h"
#include "algos/training/on_policy_trainer.h"
#include "common/mpi_context.h"

namespace bsg::algos {
namespace {

namespace fs = std::filesystem;

Eigen::MatrixXd two_cost_columns(const testing::SyntheticBatch& batch) {
  Eigen::MatrixXd costs(batch.advantages.size(), 2);
  costs.col(0) = batch.cost_advantages;
  costs.col(1) = (0.3 * batch.advantages).array() - 0.1;
  return costs;
}

TEST(SeveralConstraintsMpi, GradientsOfASplitBatchEqualTheWholeBatchOnOneRank) {
  const MpiContext world = MpiContext::world();
  ASSERT_EQ(world.size(), 2);
  testing::SyntheticBatch whole(128, 7, 8);
  const Eigen::MatrixXd costs = two_cost_columns(whole);
  // One rank with all 128 samples.
  PolicySurrogate all(whole.observations, whole.actions, whole.old_log_probs, whole.advantages, costs);
  const ConstraintGradients expected = averaged_constraint_gradients(
      PolicyUpdateInputs{whole.policy, all, 0.0, 1.0, MpiContext::single_process()});
  // Two ranks with 64 each: the average of equal-size halves is the whole mean.
  const Eigen::Index first = 64 * world.rank();
  PolicySurrogate half(whole.observations.middleRows(first, 64), whole.actions.middleRows(first, 64),
                       whole.old_log_probs.segment(first, 64), whole.advantages.segment(first, 64),
                       costs.middleRows(first, 64));
  const ConstraintGradients split =
      averaged_constraint_gradients(PolicyUpdateInputs{whole.policy, half, 0.0, 1.0, world});
  EXPECT_LT((split.reward - expected.reward).norm(), 1e-12 * (1.0 + expected.reward.norm()));
  EXPECT_LT((split.costs - expected.costs).norm(), 1e-12 * (1.0 + expected.costs.norm()));
}

TEST(SeveralConstraintsMpi, PooledConstraintCostsEqualThoseOfAllEpisodesOnOneRank) {
  const MpiContext world = MpiContext::world();
  // Rank r completes episodes whose constraint costs are (r + 1, 10 r) and (2, 3): all four on one rank
  // would have means (1 + 2 + 2 + 2) / 4 = 1.75 and (0 + 3 + 10 + 3) / 4 = 4.
  Buffer buffer(4, 1, 1, BufferOptions{0.99, 0.95, 0.95, 2});
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(1);
  const double r = world.rank();
  Eigen::VectorXd first(2), second(2), values = Eigen::VectorXd::Zero(2);
  first << r + 1.0, 10.0 * r;
  second << 2.0, 3.0;
  for (const Eigen::VectorXd* costs : {&first, &second}) {
    buffer.store(zero, zero, 0.0, 1.0, *costs, 0.0, values, 0.0);
    buffer.store(zero, zero, 0.0, 0.0, Eigen::VectorXd::Zero(2), 0.0, values, 0.0);
    buffer.finish_path(0.0, values, std::nullopt, PathEnd::episode_end);
  }
  const EpisodeStatistics pooled = pool_episode_statistics(buffer, world, true);
  ASSERT_EQ(pooled.constraint_costs.size(), 2u);
  EXPECT_EQ(pooled.constraint_costs[0].count, 4);
  EXPECT_DOUBLE_EQ(pooled.constraint_costs[0].mean, 1.75);
  EXPECT_DOUBLE_EQ(pooled.constraint_costs[1].mean, 4.0);
  EXPECT_EQ(pooled.constraint_costs[1].max, 10.0);
  EXPECT_EQ(pooled.episode_cost.mean, 1.0);
}

TEST(SeveralConstraintsMpi, ATwoConstraintRunKeepsTheRanksIdentical) {
  const MpiContext world = MpiContext::world();
  RunConfig config;
  config.env_id = "SafetyBallRun-v0";
  config.alg = Algorithm::lag_trpo;
  config.use_cost_value_function = true;
  config.hidden_sizes = {16, 16};
  config.epochs = 3;
  config.steps_per_epoch = 800;
  config.max_ep_len = 200;
  config.eval_episodes = 2;
  config.check_freq = 1;  // the trainer checks every epoch that the ranks' parameters agree
  config.constraints = {{{"cost_outside_bounds"}, 20.0}, {{"cost_velocity_violation"}, 5.0}};
  std::string directory;
  if (world.is_root()) {
    char pattern[] = "/tmp/bsg_several_constraints_mpi_XXXXXX";
    directory = mkdtemp(pattern);
  }
  OnPolicyTrainer trainer(config, RunDirectory(fs::path(directory) / "run"), world, {});
  EXPECT_TRUE(trainer.run().finished);
  Eigen::VectorXd local(2 + trainer.actor_critic().extra_cost_values[0].net().num_parameters());
  local << trainer.algorithm().state()[0].value, trainer.algorithm().state()[1].value,
      trainer.actor_critic().extra_cost_values[0].net().parameters();
  Eigen::VectorXd root = local;
  world.broadcast_from_root(root);
  EXPECT_EQ(world.max((root.array() != local.array()).any() ? 1.0 : 0.0), 0.0);
  if (world.is_root()) fs::remove_all(directory);
}

}  // namespace
}  // namespace bsg::algos
