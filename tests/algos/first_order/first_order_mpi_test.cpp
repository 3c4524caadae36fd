// The first-order updates under `mpirun -np 2` (docs/algorithms.md#first-order-updates):
// with one minibatch per pass, two ranks holding halves of a batch take the
// steps one process takes on the whole batch (the rank-averaged gradient of
// equal halves is the whole batch's); with many minibatches the ranks still
// end every update with the same parameters bit for bit, and stop their
// passes together.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "../algorithm_test_support.h"
#include "algos/training/make_algorithm.h"
#include "common/mpi_context.h"

namespace bsg::algos {
namespace {

using testing::SyntheticBatch;

// Rows [first, first + count) of the whole batch as a surrogate.
PolicySurrogate rows_of(const SyntheticBatch& batch, Eigen::Index first, Eigen::Index count) {
  return PolicySurrogate(batch.observations.middleRows(first, count), batch.actions.middleRows(first, count),
                         batch.old_log_probs.segment(first, count), batch.advantages.segment(first, count),
                         batch.cost_advantages.segment(first, count));
}

// The state of Simmer's budget controllers (simmer_algorithm.h); empty for the other algorithms.
std::vector<NamedScalar> simmer_state(const OnPolicyAlgorithm& algorithm) {
  std::vector<NamedScalar> controllers;
  for (const NamedScalar& entry : algorithm.state()) {
    if (entry.name.starts_with("simmer_")) controllers.push_back(entry);
  }
  return controllers;
}

RunConfig config_of(Algorithm alg) {
  RunConfig config = testing::config_for(alg);
  config.first_order.update_iters = 6;
  config.first_order.actor_lr = 0.01;
  config.first_order.max_grad_norm = 0.05;  // acts on some steps
  return config;
}

TEST(FirstOrderMpi, TwoRanksWithHalvesTakeTheStepsOfOneProcessOnTheWholeBatch) {
  const MpiContext mpi = MpiContext::world();
  ASSERT_EQ(mpi.size(), 2);
  for (const bool learned : {false, true})
  for (Algorithm alg : {Algorithm::ppo, Algorithm::ppo_lag, Algorithm::focops, Algorithm::cup, Algorithm::p3o,
                        Algorithm::ipo, Algorithm::ppo_saute, Algorithm::ppo_early_terminated, Algorithm::ppo_simmer}) {
    SCOPED_TRACE(std::string(to_string(alg)) + (learned ? " learned log sigma" : ""));
    RunConfig config = config_of(alg);
    config.first_order.policy_minibatch_size = 1000;  // one minibatch per pass
    SyntheticBatch whole(64, 21, 22);
    SyntheticBatch half(64, 21, 22);  // same policy and data
    if (learned) {  // docs/algorithms.md#learned-log-sigma: s is averaged and stepped with theta
      whole.policy.learn_log_std(0.4);
      half.policy.learn_log_std(0.4);
    }
    PolicySurrogate all = whole.surrogate();
    PolicySurrogate mine = rows_of(half, 32 * mpi.rank(), 32);
    Rng shuffle_single(1), shuffle_rank(2 + mpi.rank());  // the shuffle cannot matter with one minibatch
    const auto single = make_algorithm(config);
    const auto distributed = make_algorithm(config);
    for (double cost : {40.0, 10.0}) {
      single->update(PolicyUpdateInputs{whole.policy, all, cost, 50.0, MpiContext::single_process(), {}, &shuffle_single});
      distributed->update(PolicyUpdateInputs{half.policy, mine, cost, 50.0, mpi, {}, &shuffle_rank});
      const Eigen::VectorXd a = whole.policy.mean_net().parameters();
      const Eigen::VectorXd b = half.policy.mean_net().parameters();
      EXPECT_LT((a - b).norm(), 1e-12 * a.norm());
      EXPECT_EQ(mpi.min(b.sum()), mpi.max(b.sum()));
      EXPECT_EQ(simmer_state(*distributed), simmer_state(*single));  // ppo-simmer's budget controller
      if (learned) {
        const Eigen::VectorXd s_whole = whole.policy.log_stds(), s_half = half.policy.log_stds();
        EXPECT_LT((s_whole - s_half).norm(), 1e-12 * s_whole.norm());
        EXPECT_EQ(mpi.min(s_half.sum()), mpi.max(s_half.sum()));
        EXPECT_GT((s_whole.array() - std::log(0.4)).abs().maxCoeff(), 1e-3);  // it moved
      }
    }
  }
}

TEST(FirstOrderMpi, RanksWithDifferentDataStayInLockstepOverManyMinibatches) {
  const MpiContext mpi = MpiContext::world();
  for (Algorithm alg : {Algorithm::ppo_lag, Algorithm::focops, Algorithm::cup, Algorithm::p3o, Algorithm::ipo}) {
    SCOPED_TRACE(std::string(to_string(alg)));
    RunConfig config = config_of(alg);
    config.first_order.policy_minibatch_size = 16;  // 8 minibatches of 8 samples per rank
    config.trust_region.target_kl = 1e-4;            // the early stop acts
    SyntheticBatch batch(32, 21, 100 + static_cast<std::uint64_t>(mpi.rank()));
    PolicySurrogate surrogate = batch.surrogate();
    Rng shuffle(7 + mpi.rank());
    const auto algorithm = make_algorithm(config);
    const PolicyUpdateResult result =
        algorithm->update(PolicyUpdateInputs{batch.policy, surrogate, 40.0, 50.0, mpi, {}, &shuffle});
    const double passes = result.value("Misc/StopIter");
    EXPECT_EQ(mpi.min(passes), mpi.max(passes));
    const Eigen::VectorXd theta = batch.policy.mean_net().parameters();
    Eigen::VectorXd summed = theta;
    mpi.sum_in_place(summed);
    EXPECT_EQ(summed, 2.0 * theta);  // identical bits on both ranks (x + x = 2x exactly)
  }
}

}  // namespace
}  // namespace bsg::algos
