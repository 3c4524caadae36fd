// Under `mpirun -np 2`, with a different local batch on each rank, every
// algorithm's update leaves identical parameters (and decisions) on both
// ranks (docs/algorithms.md#across-mpi-ranks, #test-oracles): g, b, the FVP and the line-search scalars are
// averaged over ranks.
#include <gtest/gtest.h>

#include <vector>

#include "../algorithm_test_support.h"
#include "algos/training/make_algorithm.h"

namespace bsg::algos {
namespace {

using testing::SyntheticBatch;

// True on every rank iff `values` equal rank 0's bit for bit.
bool same_on_all_ranks(const MpiContext& mpi, const Eigen::VectorXd& values) {
  Eigen::VectorXd root = values;
  mpi.broadcast_from_root(root);
  const double mismatch = testing::bit_identical(root, values) ? 0.0 : 1.0;
  return mpi.max(mismatch) == 0.0;
}

TEST(AlgorithmsUnderMpi, DifferentLocalBatchesGiveIdenticalParametersOnAllRanks) {
  const MpiContext mpi = MpiContext::world();
  ASSERT_EQ(mpi.size(), 2);
  for (Algorithm alg : testing::on_policy_algorithms()) {
    for (double mean_episode_cost : {10.0, 40.0}) {
      // Same policy seed on both ranks (the loop broadcasts rank 0's parameters),
      // different batch seeds.
      SyntheticBatch batch(48, 17, 100 + mpi.rank());
      const auto algorithm = make_algorithm(testing::config_for(alg));
      const Eigen::VectorXd theta_old = batch.policy.mean_net().parameters();
      Rng shuffle(31 + mpi.rank());  // each rank shuffles its own batch (first-order updates)
      for (int epoch = 0; epoch < 2; ++epoch) {
        PolicySurrogate surrogate = batch.surrogate();
        const PolicyUpdateResult result = algorithm->update(
            PolicyUpdateInputs{batch.policy, surrogate, mean_episode_cost, 60.0, mpi, {}, &shuffle});
        EXPECT_TRUE(same_on_all_ranks(mpi, batch.policy.mean_net().parameters()))
            << algorithm->name() << " J_C=" << mean_episode_cost << " epoch " << epoch;
        // The rank-identical columns agree too (the first five are local values).
        Eigen::VectorXd shared(static_cast<Eigen::Index>(result.diagnostics.size() - kCommonDiagnosticCount));
        for (Eigen::Index i = 0; i < shared.size(); ++i) {
          shared[i] = result.diagnostics[kCommonDiagnosticCount + static_cast<std::size_t>(i)].value;
        }
        EXPECT_TRUE(same_on_all_ranks(mpi, shared)) << algorithm->name();
      }
      EXPECT_GT((batch.policy.mean_net().parameters() - theta_old).norm(), 0.0) << algorithm->name();
    }
  }
}

}  // namespace
}  // namespace bsg::algos
