// A MACPO round under `mpirun -np 2`: each rank holding half of every agent's batch, the round
// (the order drawn alike on both ranks, each agent's correction factor on its own rows, the CPO
// steps averaged over ranks) lands where one process lands on the whole batches.
#include <gtest/gtest.h>

#include <vector>

#include "../algorithm_test_support.h"
#include "algos/multi_agent/macpo_update.h"
#include "algos/multi_agent/sequential_order.h"
#include "common/mpi_context.h"

namespace bsg::algos {
namespace {

constexpr Eigen::Index kRows = 64;

// Agent k's whole batch, from its own seeds.
AgentBatch rows_of(const testing::SyntheticBatch& whole, Eigen::Index first, Eigen::Index count) {
  return {whole.observations.middleRows(first, count), whole.actions.middleRows(first, count),
          whole.old_log_probs.segment(first, count), whole.advantages.segment(first, count),
          whole.cost_advantages.segment(first, count)};
}

TEST(SequentialMpi, MacpoRoundOnHalvesEqualsOneProcessOnTheWhole) {
  const MpiContext mpi = MpiContext::world();
  ASSERT_EQ(mpi.size(), 2);
  const RunConfig config = testing::config_for(Algorithm::cpo);
  std::vector<testing::SyntheticBatch> wholes;
  for (std::uint64_t k = 0; k < 3; ++k) wholes.emplace_back(kRows, 40 + k, 50 + k);

  const std::vector<int> order = sequential_agent_order(3, 8, 2);
  EXPECT_EQ(mpi.min(order[0] * 100 + order[1] * 10 + order[2]), mpi.max(order[0] * 100 + order[1] * 10 + order[2]));
  const std::vector<double> c{-0.05, 0.02, -0.01};

  std::vector<GaussianPolicy> distributed, single;
  std::vector<AgentBatch> halves, whole_batches;
  for (const testing::SyntheticBatch& whole : wholes) {
    distributed.push_back(whole.policy);
    single.push_back(whole.policy);
    halves.push_back(rows_of(whole, mpi.rank() * kRows / 2, kRows / 2));
    whole_batches.push_back(rows_of(whole, 0, kRows));
  }
  std::vector<GaussianPolicy*> distributed_pointers, single_pointers;
  for (std::size_t k = 0; k < 3; ++k) {
    distributed_pointers.push_back(&distributed[k]);
    single_pointers.push_back(&single[k]);
  }
  const std::vector<AgentRoundStatistics> on_halves = macpo_round(distributed_pointers, halves, order, c, config, mpi);
  const std::vector<AgentRoundStatistics> on_whole =
      macpo_round(single_pointers, whole_batches, order, c, config, MpiContext::single_process());

  int accepted = 0;
  for (std::size_t k = 0; k < 3; ++k) {
    const Eigen::VectorXd& a = distributed[k].mean_net().parameters();
    const Eigen::VectorXd& b = single[k].mean_net().parameters();
    const Eigen::VectorXd& before = wholes[k].policy.mean_net().parameters();
    EXPECT_LT((a - b).norm(), 1e-10 * (b - before).norm() + 1e-14) << "agent " << k;
    EXPECT_EQ(mpi.min(a.sum()), mpi.max(a.sum()));
    accepted += on_whole[k].step_norm > 0.0 ? 1 : 0;
    EXPECT_EQ(on_halves[k].agent, on_whole[k].agent);
  }
  EXPECT_GE(accepted, 2);
}

}  // namespace
}  // namespace bsg::algos
