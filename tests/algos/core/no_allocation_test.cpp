// The hot paths allocate nothing once their workspaces are sized: the policy
// for one observation, batch forward/backward/JVP and the Fisher-vector
// product. Heap allocations are counted by tests/heap_counter.h (Eigen's
// temporaries and GEMM blocking buffers included).
#include <gtest/gtest.h>


#include "algos/trust_region/fisher_vector_product.h"
#include "algos/core/gaussian_policy.h"
#include "algos/core/value_function.h"

#include "tests/heap_counter.h"

namespace bsg::algos {
namespace {

using testing::allocations_of;

class NoAllocation : public ::testing::TestWithParam<std::pair<int, int>> {
 protected:
  void SetUp() override {
    if (!testing::heap_calls_countable()) GTEST_SKIP() << "malloc cannot be counted in this build";
  }
};

TEST_P(NoAllocation, HotPathsDoNotAllocateOnceSized) {
  const auto [observation_size, action_size] = GetParam();
  Rng rng(1);
  GaussianPolicy policy(observation_size, action_size, {64, 64}, rng);
  ValueFunction value(observation_size, {64, 64}, rng);
  const Eigen::VectorXd observation = Eigen::VectorXd::Constant(observation_size, 0.3);
  Eigen::VectorXd action(action_size);
  MlpSampleWorkspace sample_workspace;
  policy.sample_action(observation, action, rng, sample_workspace);  // sizes the workspace
  EXPECT_EQ(allocations_of([&] { policy.sample_action(observation, action, rng, sample_workspace); }), 0);
  EXPECT_EQ(allocations_of([&] { policy.mean_action(observation, action, sample_workspace); }), 0);
  MlpSampleWorkspace value_workspace;
  value.predict(observation, value_workspace);
  EXPECT_EQ(allocations_of([&] { value.predict(observation, value_workspace); }), 0);

  const Eigen::MatrixXd batch = Eigen::MatrixXd::Constant(8000, observation_size, 0.1);
  const Eigen::MatrixXd output_gradients = Eigen::MatrixXd::Constant(8000, action_size, 0.2);
  Eigen::VectorXd gradient(policy.mean_net().num_parameters());
  const Eigen::VectorXd direction = Eigen::VectorXd::Constant(gradient.size(), 0.01);
  MlpBatchWorkspace workspace;
  policy.mean_net().forward_batch(batch, workspace);
  policy.mean_net().backward_batch(output_gradients, workspace, gradient);
  policy.mean_net().jvp_batch(direction, workspace);
  EXPECT_EQ(allocations_of([&] { policy.mean_net().forward_batch(batch, workspace); }), 0);
  EXPECT_EQ(allocations_of([&] { policy.mean_net().backward_batch(output_gradients, workspace, gradient); }), 0);
  EXPECT_EQ(allocations_of([&] { policy.mean_net().jvp_batch(direction, workspace); }), 0);

  FisherVectorProduct fvp(policy, batch, MpiContext::single_process());
  Eigen::VectorXd product(gradient.size());
  fvp.apply(direction, product);
  EXPECT_EQ(allocations_of([&] { fvp.apply(direction, product); }), 0);
}

INSTANTIATE_TEST_SUITE_P(PolicySizes, NoAllocation,
                         ::testing::Values(std::pair<int, int>{8, 2}, std::pair<int, int>{83, 8}));

}  // namespace
}  // namespace bsg::algos
