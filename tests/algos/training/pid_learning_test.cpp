// The PID Lagrangian's purpose, measured on a short budget (docs/algorithms.md,
// PID Lagrangian): TRPO-L on SafetyBallCircle-v0 (d = 25) with the shipped PID
// gains against TRPO-L's own SGD multiplier rule, same seeds 0-3 and budget
// (60 epochs of 16 000 steps). Over the second half of training, averaged over
// the seeds, the PID runs' epoch cost must spread less (standard deviation over
// epochs), stay within 10 % of d in the mean, and give a return no more than
// 10 % below the SGD runs' (on this budget it is about 20 % above). The
// reference is the SGD rule's own runs, not a recorded number; the runs are
// deterministic. The figures at the report's batch (150 x 32 000 steps, seeds
// 0-7) are in docs/algorithms.md; `bsg_pid_learning_bench` repeats the
// comparison for any budget and gains.
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
constexpr int kSeeds = 4;
constexpr int kEpochs = 60;
constexpr int kStepsPerEpoch = 16000;

SecondHalf seed_average(const std::string& lambda_optimizer) {
  SecondHalf sum;
  for (int seed = 0; seed < kSeeds; ++seed) {
    const SecondHalf one = train_ball_circle_second_half(lambda_optimizer, seed, kEpochs, kStepsPerEpoch, {});
    std::printf("  %s seed %d: cost %.2f +- %.2f, return %.1f\n", lambda_optimizer.c_str(), seed, one.cost_mean,
                one.cost_std, one.return_mean);
    sum.cost_mean += one.cost_mean / kSeeds;
    sum.cost_std += one.cost_std / kSeeds;
    sum.return_mean += one.return_mean / kSeeds;
  }
  return sum;
}

TEST(PidLearning, TheShippedGainsSteadyTheEpochCostOfTrpoLOnBallCircleAtTheSameCostAndReturn) {
#if defined(__SANITIZE_ADDRESS__)
  // Eight training runs take about 4 CPU minutes optimised and over an hour
  // under ASan; the PID code itself runs under the sanitizers in
  // pid_lagrangian_test.cpp and the checkpoint tests.
  GTEST_SKIP() << "eight training runs are too slow under the sanitizers";
#endif
  const SecondHalf sgd = seed_average("SGD");
  const SecondHalf pid = seed_average("PID");
  EXPECT_LT(pid.cost_std, sgd.cost_std) << "PID cost std " << pid.cost_std << ", SGD " << sgd.cost_std;
  EXPECT_NEAR(pid.cost_mean, kCostLimit, 0.1 * kCostLimit);
  EXPECT_GE(pid.return_mean, sgd.return_mean - 0.1 * std::abs(sgd.return_mean))
      << "PID return " << pid.return_mean << ", SGD " << sgd.return_mean;
}

}  // namespace pid_learning_test
}  // namespace
