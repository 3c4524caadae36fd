// The backtracking line searches (docs/algorithms.md#trpo-line-search, #constrained-line-search) on closed-form 1-D problems
// whose accepted trial is worked out by hand.
#include "algos/trust_region/line_search.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

namespace bsg::algos {
namespace {

const MpiContext kSingle = MpiContext::single_process();

// loss(theta) = (theta - 1)^2 at theta_old = 0 (loss_old = 1), KL = theta^2 / 2.
LossAndKl parabola(const Eigen::Ref<const Eigen::VectorXd>& step) {
  const double theta = step[0];
  return {(theta - 1.0) * (theta - 1.0), 0.5 * theta * theta};
}

TEST(TrpoLineSearch, AcceptsTheFirstImprovingFractionInsideTheTrustRegion) {
  // Full step 4: trial s_j = 4 * 0.8^j improves iff s_j <= 2, first at j = 4
  // (s = 1.6384, KL = 1.342 <= 1.5 * 1).
  const auto result = trpo_line_search(Eigen::VectorXd::Constant(1, 4.0), 1.0, parabola, kSingle,
                                       {.budget = 15, .decay = 0.8, .target_kl = 1.0});
  EXPECT_EQ(result.acceptance_step, 5);
  EXPECT_DOUBLE_EQ(result.step[0], 4.0 * std::pow(0.8, 4));
  EXPECT_NEAR(result.improvement, 1.0 - std::pow(4.0 * std::pow(0.8, 4) - 1.0, 2), 1e-15);
  EXPECT_NEAR(result.kl, 0.5 * std::pow(4.0 * std::pow(0.8, 4), 2), 1e-15);
}

TEST(TrpoLineSearch, KlToleranceIsOneAndAHalfTargetKl) {
  // delta = 0.5: KL_j = s_j^2 / 2 <= 0.75 first at j = 6 (s = 1.048576).
  const auto result = trpo_line_search(Eigen::VectorXd::Constant(1, 4.0), 1.0, parabola, kSingle,
                                       {.budget = 15, .decay = 0.8, .target_kl = 0.5});
  EXPECT_EQ(result.acceptance_step, 7);
  // kl_accept_factor = 1 (the report's delta): s^2 / 2 <= 0.5 first at j = 7.
  const auto strict = trpo_line_search(Eigen::VectorXd::Constant(1, 4.0), 1.0, parabola, kSingle,
                                       {.budget = 15, .decay = 0.8, .target_kl = 0.5, .kl_accept_factor = 1.0});
  EXPECT_EQ(strict.acceptance_step, 8);
}

TEST(TrpoLineSearch, ExhaustedBudgetGivesAZeroStep) {
  int calls = 0;
  const auto counting = [&](const Eigen::Ref<const Eigen::VectorXd>& step) {
    ++calls;
    return parabola(step);
  };
  const auto result = trpo_line_search(Eigen::VectorXd::Constant(1, 4.0), 1.0, counting, kSingle,
                                       {.budget = 4, .decay = 0.8, .target_kl = 1.0});
  EXPECT_FALSE(result.accepted());
  EXPECT_EQ(result.acceptance_step, 0);
  EXPECT_EQ(result.step[0], 0.0);
  EXPECT_EQ(calls, 4);
}

TEST(TrpoLineSearch, RejectsNonFiniteLosses) {
  const auto nan_until_small = [](const Eigen::Ref<const Eigen::VectorXd>& step) {
    LossAndKl value = parabola(step);
    if (step[0] > 0.5) value.loss = std::numeric_limits<double>::quiet_NaN();
    return value;
  };
  // Would accept j = 0 (s = 1, improvement 1) without the NaN; first s <= 0.5 is j = 4 (0.4096).
  const auto result = trpo_line_search(Eigen::VectorXd::Constant(1, 1.0), 1.0, nan_until_small, kSingle,
                                       {.budget = 15, .decay = 0.8, .target_kl = 1.0});
  EXPECT_EQ(result.acceptance_step, 4 + 1);
}

// Constrained: reward loss (theta - 1)^2, cost surrogate L_C = theta, KL = theta^2 / 2.
ConstrainedTrial constrained_parabola(const Eigen::Ref<const Eigen::VectorXd>& step) {
  const double theta = step[0];
  return {(theta - 1.0) * (theta - 1.0), theta, 0.5 * theta * theta};
}

TEST(ConstrainedLineSearch, CostIncreaseIsLimitedByMinusC) {
  // c = -0.5: D_j = s_j <= 0.5. Full step 1: first at j = 4 (0.4096); reward improves there too.
  const ConstrainedLineSearchInputs inputs{.reward_loss_old = 1.0, .cost_surrogate_old = 0.0,
                                           .constraint_violation = -0.5, .require_reward_improvement = true};
  const auto result = constrained_line_search(Eigen::VectorXd::Constant(1, 1.0), inputs, constrained_parabola,
                                              kSingle, {.budget = 20, .decay = 0.8, .target_kl = 1.0});
  EXPECT_EQ(result.acceptance_step, 4 + 1);
  EXPECT_NEAR(result.cost_change, std::pow(0.8, 4), 1e-15);
}

TEST(ConstrainedLineSearch, InfeasibleCaseSkipsTheRewardTestButForbidsCostIncrease) {
  // c = +0.2: D_j <= 0. A step of -1 lowers the cost but worsens the reward loss.
  ConstrainedLineSearchInputs inputs{.reward_loss_old = 1.0, .cost_surrogate_old = 0.0,
                                     .constraint_violation = 0.2, .require_reward_improvement = false};
  const LineSearchOptions options{.budget = 20, .decay = 0.8, .target_kl = 1.0};
  const auto recovery = constrained_line_search(Eigen::VectorXd::Constant(1, -1.0), inputs, constrained_parabola,
                                                kSingle, options);
  EXPECT_EQ(recovery.acceptance_step, 1);
  EXPECT_EQ(recovery.step[0], -1.0);
  // With the reward test on (CPO cases >= 2), the same step is never accepted.
  inputs.require_reward_improvement = true;
  const auto feasible = constrained_line_search(Eigen::VectorXd::Constant(1, -1.0), inputs, constrained_parabola,
                                                kSingle, options);
  EXPECT_FALSE(feasible.accepted());
  EXPECT_EQ(feasible.step[0], 0.0);
  // A cost-increasing step is rejected whenever c >= 0.
  inputs.require_reward_improvement = false;
  const auto increase = constrained_line_search(Eigen::VectorXd::Constant(1, 0.5), inputs, constrained_parabola,
                                                kSingle, options);
  EXPECT_FALSE(increase.accepted());
}

TEST(ConstrainedLineSearch, RejectsTrialsWithAnyNonFiniteValue) {
  // Q12: the original only rejects when both are NaN; here one NaN suffices.
  const auto nan_cost = [](const Eigen::Ref<const Eigen::VectorXd>& step) {
    ConstrainedTrial trial = constrained_parabola(step);
    if (step[0] > 0.3) trial.cost_surrogate = std::numeric_limits<double>::quiet_NaN();
    return trial;
  };
  const ConstrainedLineSearchInputs inputs{.reward_loss_old = 1.0, .cost_surrogate_old = 0.0,
                                           .constraint_violation = -1.0, .require_reward_improvement = true};
  const auto result = constrained_line_search(Eigen::VectorXd::Constant(1, 0.5), inputs, nan_cost, kSingle,
                                              {.budget = 20, .decay = 0.8, .target_kl = 1.0});
  // 0.5 * 0.8^2 = 0.32 > 0.3 is NaN; the first finite trial is j = 3 (0.256).
  EXPECT_EQ(result.acceptance_step, 3 + 1);
}

TEST(LineSearch, BadOptionsGiveExceptions) {
  const Eigen::VectorXd step = Eigen::VectorXd::Constant(1, 1.0);
  EXPECT_THROW(trpo_line_search(step, 1.0, parabola, kSingle, {.budget = 0}), std::invalid_argument);
  EXPECT_THROW(trpo_line_search(step, 1.0, parabola, kSingle, {.decay = 1.0}), std::invalid_argument);
  EXPECT_THROW(trpo_line_search(step, 1.0, parabola, kSingle, {.target_kl = 0.0}), std::invalid_argument);
  EXPECT_THROW(trpo_line_search(step, 1.0, LossEvaluator{}, kSingle, {}), std::invalid_argument);
  EXPECT_THROW(constrained_line_search(step, {}, constrained_parabola, kSingle, {.kl_accept_factor = 0.0}),
               std::invalid_argument);
}

}  // namespace
}  // namespace bsg::algos
