// The unlearning of issue 27 and its correction, on a short budget
// (docs/algorithms.md#reward-scaling-and-unlearning): TRPO (delta 0.01) on
// SafetyBallRun-v0, seed 2, the first 12 of the report's 100 epochs (the
// noise annealing of a 100-epoch run). With the faithful learner the return
// peaks around epoch 5 and has lost more than half of its peak by epoch 11;
// with `learner: corrected` (Q19's rescaled V among its switches) it is still
// within 10 % of its peak. The reference of each is its own peak, not a
// recorded number; the runs are deterministic. The 100-epoch figures of
// 4 seeds are in docs/algorithms.md.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "../../test_support.h"
#include "algos/training/on_policy_trainer.h"
#include "common/mpi_context.h"
#include "common/run_config_resolve.h"

namespace bsg::algos {
namespace {

constexpr int kEpochs = 12;

// The mean training return of each of the first kEpochs epochs.
std::vector<double> ball_run_returns(const std::string& learner) {
  RunConfigRequest request;
  request.configs_dir = std::filesystem::path(BSG_SOURCE_DIR) / "configs";
  request.set_arguments = {"env_id=SafetyBallRun-v0", "alg=trpo", "seed=2", "target_kl=0.01", "eval_episodes=0",
                           "learner=" + learner};
  const RunConfig config = resolve_run_config(request).config;
  const testing::TemporaryDirectory directory;
  TrainerOptions options;
  options.stop_after_epochs = kEpochs;
  OnPolicyTrainer trainer(config, RunDirectory(directory.path() / "run"), MpiContext::single_process(), options);
  if (trainer.run().epochs_completed != kEpochs) throw std::runtime_error("training stopped early");
  std::vector<double> returns = testing::read_csv_columns(directory.path() / "run" / "progress.csv")["episode_return_mean"];
  std::printf("  %s:", learner.c_str());
  for (const double value : returns) std::printf(" %.0f", value);
  std::printf("\n");
  return returns;
}

TEST(BallRunUnlearning, TheFaithfulLearnerLosesItsPeakAndTheCorrectedOneKeepsIt) {
#if defined(__SANITIZE_ADDRESS__)
  // Two runs of 12 x 32 000 BallRun steps take about 40 CPU seconds optimised
  // and far longer under ASan; the switches themselves run under the
  // sanitizers in reward_scaling_switches_test.cpp.
  GTEST_SKIP() << "two BallRun training runs are too slow under the sanitizers";
#endif
  const std::vector<double> faithful = ball_run_returns("faithful");
  const std::vector<double> corrected = ball_run_returns("corrected");
  ASSERT_EQ(faithful.size(), static_cast<std::size_t>(kEpochs));
  ASSERT_EQ(corrected.size(), static_cast<std::size_t>(kEpochs));
  const double faithful_peak = *std::max_element(faithful.begin(), faithful.end());
  const double corrected_peak = *std::max_element(corrected.begin(), corrected.end());
  EXPECT_GT(faithful_peak, 500.0);  // it did learn to run before unlearning
  EXPECT_LT(faithful.back(), 0.5 * faithful_peak);
  EXPECT_GE(corrected.back(), 0.9 * corrected_peak);
  EXPECT_GT(corrected.back(), faithful.back());
}

}  // namespace
}  // namespace bsg::algos
