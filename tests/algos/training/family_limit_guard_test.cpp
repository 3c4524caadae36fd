// Family guards (docs/algorithms.md#family-guards): a learner family whose
// learner ignores the cost limit must fail CI. One short run of each family's
// guard learner at its shipped defaults on SafetyBallCircle-v0, seed 0, 25
// epochs of 4000 steps, against d = 10 and against d = 40: the mean episode
// cost over the last 10 epochs must end on the right side of the midpoint 25
// of the two limits for each (the d = 10 run below it, the d = 40 run above
// it). A learner that ignored d would end both runs at the same cost, on one
// side. Measured with the shipped defaults (last-10 costs, d = 10 / d = 40):
// TRPO-L 0.0 / 38.8, CPPO-PID 12.3 / 37.5; PPO-Lag's Adam multiplier
// (OmniSafe's rate) fails it, 46.0 / 50.0, which docs/algorithms.md#ppo-lag
// explains. Each run is deterministic; each test takes 7-14 s of CPU.
#include <gtest/gtest.h>

#include <filesystem>
#include <numeric>
#include <string>
#include <vector>

#include "../../test_support.h"
#include "algos/training/on_policy_trainer.h"
#include "common/mpi_context.h"
#include "common/run_config_resolve.h"

namespace {

namespace fs = std::filesystem;

constexpr double kLowLimit = 10.0;
constexpr double kHighLimit = 40.0;
constexpr double kMidpoint = 0.5 * (kLowLimit + kHighLimit);
constexpr std::size_t kLastEpochs = 10;

// The mean of episode_cost_mean over the last 10 of 25 epochs of `alg` against limit d.
double final_cost(const std::string& alg, double cost_limit, const std::vector<std::string>& settings) {
  bsg::RunConfigRequest request;
  request.configs_dir = fs::path(BSG_SOURCE_DIR) / "configs";
  request.set_arguments = {"env_id=SafetyBallCircle-v0", "alg=" + alg,           "seed=0",
                           "epochs=25",                  "steps_per_epoch=4000", "eval_episodes=0",
                           "cost_limit=" + std::to_string(cost_limit)};
  request.set_arguments.insert(request.set_arguments.end(), settings.begin(), settings.end());
  const bsg::RunConfig config = bsg::resolve_run_config(request).config;
  const bsg::testing::TemporaryDirectory directory;
  bsg::algos::OnPolicyTrainer trainer(config, bsg::algos::RunDirectory(directory.path() / "run"),
                                      bsg::MpiContext::single_process(), {});
  EXPECT_TRUE(trainer.run().finished);
  const std::vector<double> costs =
      bsg::testing::read_csv_columns(directory.path() / "run" / "progress.csv").at("episode_cost_mean");
  if (costs.size() < kLastEpochs) {
    ADD_FAILURE() << "only " << costs.size() << " epochs logged";
    return 0.0;
  }
  return std::accumulate(costs.end() - kLastEpochs, costs.end(), 0.0) / static_cast<double>(kLastEpochs);
}

void expect_costs_follow_the_limit(const std::string& alg, const std::vector<std::string>& settings) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "two training runs take minutes under the sanitizers";
#endif
  const double low = final_cost(alg, kLowLimit, settings);
  const double high = final_cost(alg, kHighLimit, settings);
  EXPECT_LT(low, kMidpoint) << alg << ": last-10 cost " << low << " at d = 10, " << high << " at d = 40";
  EXPECT_GT(high, kMidpoint) << alg << ": last-10 cost " << low << " at d = 10, " << high << " at d = 40";
}

}  // namespace

TEST(FamilyLimitGuard, TrustRegionTrpoLEndsOnEachLimitsSide) { expect_costs_follow_the_limit("lag-trpo", {}); }

TEST(FamilyLimitGuard, FirstOrderCppoPidEndsOnEachLimitsSide) {
  expect_costs_follow_the_limit("ppo-lag", {"lambda_optimizer=PID"});
}
