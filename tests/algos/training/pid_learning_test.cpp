// The PID Lagrangian's purpose, measured on a short budget (docs/algorithms.md,
// PID Lagrangian): TRPO-L on SafetyBallCircle-v0 (d = 25) with the shipped PID
// gains against TRPO-L's own SGD multiplier rule, same seed and budget (60
// epochs of 16 000 steps). Seed 3 is the one of seeds 0-3 where the SGD rule's
// pure integral winds up (lambda to 13.5, the cost held near 0 for 15 epochs),
// the failure the PID terms exist to prevent; on the other three the two rules
// spread the cost alike at this budget. Over the second half of training the
// PID run's epoch cost must spread less (standard deviation over epochs), its
// mean stay nearer d than the SGD run's and at most 10 % above it, and its
// return be no more than 10 % below the SGD run's (measured: cost 20.13 +- 5.92,
// return 184.2, against 14.64 +- 12.60 and 105.7). The reference is the SGD rule's own run, not a recorded number;
// the runs are deterministic. The four-seed comparison and the figures at the
// report's batch (150 x 32 000 steps, seeds 0-7) are in docs/algorithms.md;
// `bsg_pid_learning_bench` repeats the comparison for any budget and gains.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "../cost_steadiness.h"

namespace {
namespace pid_learning_test {

using bsg::testing::SecondHalf;
using bsg::testing::train_ball_circle_second_half;

constexpr double kCostLimit = 25.0;
constexpr int kWindUpSeed = 3;
constexpr int kEpochs = 60;
constexpr int kStepsPerEpoch = 16000;

SecondHalf train(const std::string& lambda_optimizer) {
  const SecondHalf run = train_ball_circle_second_half(lambda_optimizer, kWindUpSeed, kEpochs, kStepsPerEpoch, {});
  std::printf("  %s seed %d: cost %.2f +- %.2f, return %.1f\n", lambda_optimizer.c_str(), kWindUpSeed, run.cost_mean,
              run.cost_std, run.return_mean);
  return run;
}

TEST(PidLearning, TheShippedGainsKeepTrpoLFromWindingUpOnBallCircleAtTheSameCostAndReturn) {
#if defined(__SANITIZE_ADDRESS__)
  // Training runs are slow under ASan (eight of these took over an hour);
  // the PID code itself runs under the sanitizers in
  // pid_lagrangian_test.cpp and the checkpoint tests.
  GTEST_SKIP() << "two training runs are too slow under the sanitizers";
#endif
  const SecondHalf sgd = train("SGD");
  const SecondHalf pid = train("PID");
  EXPECT_LT(pid.cost_std, sgd.cost_std) << "PID cost std " << pid.cost_std << ", SGD " << sgd.cost_std;
  EXPECT_LT(std::abs(pid.cost_mean - kCostLimit), std::abs(sgd.cost_mean - kCostLimit))
      << "PID cost mean " << pid.cost_mean << ", SGD " << sgd.cost_mean;
  EXPECT_LE(pid.cost_mean, 1.1 * kCostLimit);
  EXPECT_GE(pid.return_mean, sgd.return_mean - 0.1 * std::abs(sgd.return_mean))
      << "PID return " << pid.return_mean << ", SGD " << sgd.return_mean;
}

}  // namespace pid_learning_test
}  // namespace
