// The trust-region tools under `mpirun -np 2`: rank averages equal the
// single-process results over the union of both ranks' data, and everything
// that must agree across ranks does.
#include <gtest/gtest.h>

#include "algos/trust_region/fisher_vector_product.h"
#include "algos/core/gaussian_policy.h"
#include "algos/trust_region/line_search.h"
#include "algos/core/policy_surrogate.h"
#include "algos/core/value_function.h"
#include "common/mpi_context.h"

namespace bsg::algos {
namespace {

Eigen::MatrixXd rank_observations(int rank, Eigen::Index rows, int columns) {
  Rng rng(500 + rank);
  Eigen::MatrixXd m(rows, columns);
  for (Eigen::Index i = 0; i < m.size(); ++i) m.data()[i] = standard_normal(rng) + rank;
  return m;
}

Eigen::MatrixXd every_fourth_row(const Eigen::MatrixXd& m) {
  Eigen::MatrixXd rows((m.rows() + 3) / 4, m.cols());
  for (Eigen::Index i = 0; i < rows.rows(); ++i) rows.row(i) = m.row(4 * i);
  return rows;
}

// The same initial policy on every rank (same seed), as after the broadcast.
GaussianPolicy shared_policy() {
  Rng rng(99);
  GaussianPolicy policy(5, 2, {16, 16}, rng);
  policy.set_std(0.3);
  return policy;
}

TEST(TrustRegionMpi, FisherVectorProductEqualsSingleProcessOverUnionOfSubBatches) {
  const MpiContext mpi = MpiContext::world();
  ASSERT_EQ(mpi.size(), 2);
  const GaussianPolicy policy = shared_policy();
  const Eigen::MatrixXd local = rank_observations(mpi.rank(), 40, 5);
  FisherVectorProduct distributed(policy, local, mpi);
  Eigen::MatrixXd union_rows(20, 5);
  union_rows << every_fourth_row(rank_observations(0, 40, 5)), every_fourth_row(rank_observations(1, 40, 5));
  FisherVectorProduct single(policy, union_rows, MpiContext::single_process(),
                             FisherVectorProductOptions{.subsample_stride = 1});
  Rng rng(3);
  Eigen::VectorXd v(policy.mean_net().num_parameters());
  for (Eigen::Index k = 0; k < v.size(); ++k) v[k] = standard_normal(rng);
  Eigen::VectorXd a(v.size()), b(v.size());
  distributed.apply(v, a);
  single.apply(v, b);
  EXPECT_LT((a - b).norm() / b.norm(), 1e-13);
  EXPECT_EQ(mpi.min(a.sum()), mpi.max(a.sum()));
}

TEST(TrustRegionMpi, AveragedGradientEqualsMeanOfPerRankGradients) {
  const MpiContext mpi = MpiContext::world();
  const GaussianPolicy policy = shared_policy();
  const auto rank_gradient = [&](int rank) {
    const Eigen::Index n = 24;
    const Eigen::MatrixXd obs = rank_observations(rank, n, 5);
    Rng rng(700 + rank);
    Eigen::MatrixXd actions(n, 2);
    Eigen::VectorXd log_probs(n), advantages(n), cost_advantages(n);
    MlpSampleWorkspace workspace;
    for (Eigen::Index i = 0; i < n; ++i) {
      Eigen::VectorXd action(2);
      log_probs[i] = policy.sample_action(obs.row(i).transpose(), action, rng, workspace);
      actions.row(i) = action.transpose();
      advantages[i] = standard_normal(rng);
      cost_advantages[i] = standard_normal(rng);
    }
    PolicySurrogate surrogate(obs, actions, log_probs, advantages, cost_advantages);
    Eigen::VectorXd g(policy.mean_net().num_parameters());
    surrogate.gradient(policy, 1.0, 0.0, g);
    return g;
  };
  Eigen::VectorXd g = rank_gradient(mpi.rank());
  mpi.average_in_place(g);  // g = avg grad L_R
  const Eigen::VectorXd expected = 0.5 * (rank_gradient(0) + rank_gradient(1));
  EXPECT_LT((g - expected).norm() / expected.norm(), 1e-14);
}

TEST(TrustRegionMpi, BroadcastPolicyParametersAreIdenticalOnAllRanks) {
  const MpiContext mpi = MpiContext::world();
  Rng rng(1234 + mpi.rank());  // every rank draws its own initial weights (docs/algorithms.md#networks)
  GaussianPolicy policy(5, 2, {16, 16}, rng);
  Eigen::VectorXd theta = policy.mean_net().parameters();
  mpi.broadcast_from_root(theta);
  policy.mean_net().set_parameters(theta);
  Rng root_rng(1234);
  const GaussianPolicy root_policy(5, 2, {16, 16}, root_rng);
  EXPECT_EQ(policy.mean_net().parameters(), root_policy.mean_net().parameters());
}

TEST(TrustRegionMpi, ValueFitKeepsParametersIdenticalAcrossRanks) {
  const MpiContext mpi = MpiContext::world();
  Rng init_rng(42);  // same initial net everywhere
  ValueFunction value(5, {16, 16}, init_rng);
  Rng rank_rng(42 + 10000 * mpi.rank());  // different shuffles per rank
  const Eigen::MatrixXd obs = rank_observations(mpi.rank(), 256, 5);
  const Eigen::VectorXd targets = obs.rowwise().sum();
  const ValueFitStats stats = value.fit(obs, targets, rank_rng, mpi);
  EXPECT_EQ(stats.adam_steps, 80);
  const double sum = value.net().parameters().sum();
  EXPECT_EQ(mpi.min(sum), mpi.max(sum));
}

TEST(TrustRegionMpi, LineSearchDecidesOnRankAveragesIdenticallyOnAllRanks) {
  const MpiContext mpi = MpiContext::world();
  // Rank 0's local loss gets worse, rank 1's improves by more: the average improves.
  const double sign = mpi.rank() == 0 ? 1.0 : -3.0;
  const auto evaluate = [&](const Eigen::Ref<const Eigen::VectorXd>& step) {
    return LossAndKl{sign * step[0], 0.0};
  };
  const auto result = trpo_line_search(Eigen::VectorXd::Constant(1, 1.0), 0.0, evaluate, mpi,
                                       {.budget = 15, .decay = 0.8, .target_kl = 0.01});
  EXPECT_EQ(result.acceptance_step, 1);
  EXPECT_DOUBLE_EQ(result.improvement, 1.0);  // avg(0 - (1, -3))
  // A non-finite loss on one rank only rejects the trial on both.
  const auto nan_on_rank_one = [&](const Eigen::Ref<const Eigen::VectorXd>& step) {
    const bool bad = mpi.rank() == 1 && step[0] > 0.7;
    return LossAndKl{bad ? std::nan("") : -step[0], 0.0};
  };
  const auto guarded = trpo_line_search(Eigen::VectorXd::Constant(1, 1.0), 0.0, nan_on_rank_one, mpi,
                                        {.budget = 15, .decay = 0.8, .target_kl = 0.01});
  EXPECT_EQ(guarded.acceptance_step, 3);  // 1, 0.8 rejected; 0.64 accepted
  EXPECT_EQ(mpi.min(guarded.acceptance_step), mpi.max(guarded.acceptance_step));
}

}  // namespace
}  // namespace bsg::algos
