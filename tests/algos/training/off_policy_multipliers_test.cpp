// When an off-policy -lag run's multipliers step and on which cost (algos/training/
// off_policy_multipliers.h), on hand-made sequences of episode costs against hand computations:
// the SGD rule lambda <- max(0, lambda + lr (J - d)) (lr 0.1, d 25, lambda_0 0.5) and one Adam
// step per round, which moves lambda by lambda_lr whatever the size of a violation.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "algos/training/off_policy_multipliers.h"
#include "common/mpi_context.h"
#include "common/run_config_resolve.h"

namespace bsg::algos {
namespace {

// The shipped configs/algorithms/<alg>.yaml on BallCircle at d = 25, with the given settings on top.
RunConfig ball_circle_config(const std::string& alg, const std::vector<std::string>& settings = {}) {
  RunConfigRequest request;
  request.configs_dir = std::filesystem::path(BSG_SOURCE_DIR) / "configs";
  request.set_arguments = {"env_id=SafetyBallCircle-v0", "alg=" + alg, "cost_limit=25"};
  request.set_arguments.insert(request.set_arguments.end(), settings.begin(), settings.end());
  return resolve_run_config(request).config;
}

RunConfig td3_lag_config(const std::vector<std::string>& settings) { return ball_circle_config("td3-lag", settings); }

RunConfig sgd_config(const std::string& schedule) {
  return td3_lag_config({"lambda_optimizer=SGD", "lambda_lr=0.1", "lagrangian_multiplier_init=0.5",
                         "multiplier_window=2", "multiplier_schedule=" + schedule});
}

// Episode costs of one constraint, as the collector lists an epoch's completed episodes.
struct Episodes {
  std::vector<std::vector<double>> costs{{}};
  std::size_t recorded = 0;
  void complete(OffPolicyMultipliers& multipliers, const std::vector<double>& new_costs) {
    costs[0].insert(costs[0].end(), new_costs.begin(), new_costs.end());
    multipliers.record(costs, recorded);
    recorded = costs[0].size();
  }
};

TEST(OffPolicyMultipliers, UpdateRoundStepsBeforeEveryLearningRoundOnTheLastWindowEpisodes) {
  const MpiContext mpi = MpiContext::single_process();
  OffPolicyMultipliers multipliers(sgd_config("update_round"));
  ASSERT_EQ(multipliers.schedule(), MultiplierSchedule::update_round);
  const auto lambda = [&] { return multipliers.multipliers().value(0); };
  Episodes episodes;
  EXPECT_FALSE(multipliers.before_gradient_round(true, mpi));  // no episode yet: no step
  EXPECT_DOUBLE_EQ(lambda(), 0.5);
  episodes.complete(multipliers, {30.0});
  EXPECT_TRUE(multipliers.before_gradient_round(true, mpi));  // window {30}: 0.5 + 0.1 * 5
  EXPECT_NEAR(lambda(), 1.0, 1e-12);
  EXPECT_FALSE(multipliers.before_gradient_round(false, mpi));  // no gradient steps: no step
  EXPECT_NEAR(lambda(), 1.0, 1e-12);
  EXPECT_TRUE(multipliers.before_gradient_round(true, mpi));  // the same window again: 1.0 + 0.5
  EXPECT_NEAR(lambda(), 1.5, 1e-12);
  episodes.complete(multipliers, {10.0, 14.0});  // 30 leaves the window of 2
  EXPECT_TRUE(multipliers.before_gradient_round(true, mpi));  // mean 12: 1.5 + 0.1 * (12 - 25)
  EXPECT_NEAR(lambda(), 0.2, 1e-12);
  episodes.complete(multipliers, {40.0});  // window {14, 40}, mean 27: 0.2 + 0.1 * 2
  EXPECT_TRUE(multipliers.before_gradient_round(true, mpi));
  EXPECT_NEAR(lambda(), 0.4, 1e-12);
  episodes.complete(multipliers, {0.0, 0.0});  // mean 0: 0.4 - 2.5 projected onto 0
  EXPECT_TRUE(multipliers.before_gradient_round(true, mpi));
  EXPECT_DOUBLE_EQ(lambda(), 0.0);
  multipliers.restart();  // the environments restart: the window empties
  EXPECT_FALSE(multipliers.before_gradient_round(true, mpi));
  EXPECT_FALSE(multipliers.after_epoch(std::vector<ConstraintEstimate>{{35.0, 25.0}}, 3));  // not this schedule
  EXPECT_DOUBLE_EQ(lambda(), 0.0);
}

TEST(OffPolicyMultipliers, EpochStepsOnceAfterTheEpochOnItsEpisodesAndNeverInARound) {
  const MpiContext mpi = MpiContext::single_process();
  OffPolicyMultipliers multipliers(sgd_config("epoch"));
  Episodes episodes;
  episodes.complete(multipliers, {30.0, 40.0});
  EXPECT_FALSE(multipliers.before_gradient_round(true, mpi));
  EXPECT_FALSE(multipliers.before_gradient_round(true, mpi));
  EXPECT_DOUBLE_EQ(multipliers.multipliers().value(0), 0.5);
  EXPECT_FALSE(multipliers.after_epoch(std::vector<ConstraintEstimate>{{35.0, 25.0}}, 0));  // no episode
  EXPECT_TRUE(multipliers.after_epoch(std::vector<ConstraintEstimate>{{35.0, 25.0}}, 2));  // 0.5 + 0.1 * 10
  EXPECT_NEAR(multipliers.multipliers().value(0), 1.5, 1e-12);
}

// Adam's first steps on a constant gradient g move by lr g / (|g| + eps) (bias-corrected moments
// m = g, v = g^2): three rounds on one violation move lambda three times lambda_lr, where the
// epoch schedule moves it once in the same epoch.
TEST(OffPolicyMultipliers, AdamMovesLambdaByItsRateInEveryRound) {
  const MpiContext mpi = MpiContext::single_process();
  OffPolicyMultipliers multipliers(td3_lag_config({"lambda_optimizer=Adam", "lambda_lr=0.001",
                                                   "lagrangian_multiplier_init=0.001", "multiplier_window=10",
                                                   "multiplier_schedule=update_round"}));
  Episodes episodes;
  episodes.complete(multipliers, {80.0, 70.0});  // J - d = 50
  const double step = 0.001 * 50.0 / (50.0 + 1e-8);
  for (int round = 1; round <= 3; ++round) {
    ASSERT_TRUE(multipliers.before_gradient_round(true, mpi));
    EXPECT_NEAR(multipliers.multipliers().value(0), 0.001 + round * step, 1e-12) << "round " << round;
  }
}

// sac-lag.yaml's multiplier: FSRL's PID gains K_P 0.05 and K_D 0.1 (delay 1), with K_I 0.05
// stepped once per epoch on the epoch's episodes (FSRL steps K_I 0.0005 before every round, which
// at 300 000 steps did not follow d: docs/benchmark.md). Hand computation with d = 25, I_0 = 0:
//   epoch 1, J = 35: I = 0.5, P = 0.05 * 10 = 0.5, D = 0.1 * (35 - 0) = 3.5, lambda = 4.5;
//   epoch 2, J = 35: I = 1.0, P = 0.5, D = 0 (no rise), lambda = 1.5;
//   epoch 3, J = 15: I = 0.5, P = -0.5, D = 0, lambda = 0.
TEST(OffPolicyMultipliers, SacLagsShippedRuleStepsTheFsrlGainsOncePerEpoch) {
  const MpiContext mpi = MpiContext::single_process();
  OffPolicyMultipliers multipliers(ball_circle_config("sac-lag"));
  ASSERT_EQ(multipliers.schedule(), MultiplierSchedule::epoch);
  const auto lambda = [&] { return multipliers.multipliers().value(0); };
  Episodes episodes;
  const double tolerance = 2e-5;  // the integral may start at 1e-5 rather than 0
  episodes.complete(multipliers, {30.0, 40.0});
  EXPECT_FALSE(multipliers.before_gradient_round(true, mpi));  // never within the epoch
  ASSERT_TRUE(multipliers.after_epoch(std::vector<ConstraintEstimate>{{35.0, 25.0}}, 2));
  EXPECT_NEAR(lambda(), 4.5, tolerance);
  ASSERT_TRUE(multipliers.after_epoch(std::vector<ConstraintEstimate>{{35.0, 25.0}}, 2));
  EXPECT_NEAR(lambda(), 1.5, tolerance);
  ASSERT_TRUE(multipliers.after_epoch(std::vector<ConstraintEstimate>{{15.0, 25.0}}, 2));
  EXPECT_NEAR(lambda(), 0.0, tolerance);
}

// td3-lag.yaml's and ddpg-lag.yaml's multiplier: TRPO-L's gradient step, once per epoch on the
// epoch's episodes, lambda_lr 0.02 from OmniSafe's 0.001 (OmniSafe's Adam step every round moved
// lambda by 2 per epoch whatever the violation, and the final policies scattered: docs/benchmark.md).
// Hand computation with d = 25: 0.001 + 0.02 * 10 = 0.201; + 0.02 * 10 = 0.401;
// + 0.02 * (5 - 25) = 0.001; 0.001 + 0.02 * (0 - 25) projected onto 0.
TEST(OffPolicyMultipliers, Td3AndDdpgLagsShippedRuleIsAGradientStepOncePerEpoch) {
  const MpiContext mpi = MpiContext::single_process();
  for (const std::string alg : {"td3-lag", "ddpg-lag"}) {
    SCOPED_TRACE(alg);
    OffPolicyMultipliers multipliers(ball_circle_config(alg));
    ASSERT_EQ(multipliers.schedule(), MultiplierSchedule::epoch);
    const auto lambda = [&] { return multipliers.multipliers().value(0); };
    EXPECT_DOUBLE_EQ(lambda(), 0.001);
    Episodes episodes;
    episodes.complete(multipliers, {30.0, 40.0});
    EXPECT_FALSE(multipliers.before_gradient_round(true, mpi));  // never within the epoch
    const std::vector<std::pair<double, double>> epochs_and_lambdas = {{35.0, 0.201}, {35.0, 0.401}, {5.0, 0.001}};
    for (const auto& [epoch_cost, expected] : epochs_and_lambdas) {
      ASSERT_TRUE(multipliers.after_epoch(std::vector<ConstraintEstimate>{{epoch_cost, 25.0}}, 2));
      EXPECT_NEAR(lambda(), expected, 1e-12) << "after an epoch costing " << epoch_cost;
    }
    ASSERT_TRUE(multipliers.after_epoch(std::vector<ConstraintEstimate>{{0.0, 25.0}}, 2));
    EXPECT_DOUBLE_EQ(lambda(), 0.0);
  }
}

}  // namespace
}  // namespace bsg::algos
