// The PID Lagrange multiplier (algos/lagrange/pid_lagrangian.h, Stooke, Achiam and
// Abbeel 2020, Algorithm 2): lambda sequences computed by hand for given cost
// sequences (P only, I only with its clamp, D with its delay, both EMAs, the
// upper bound), lambda >= 0 always, the integral alone equals the SGD rule,
// and the state survives a checkpoint.
#include "algos/lagrange/pid_lagrangian.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "algos/lagrange/multiplier.h"
#include "common/random.h"

namespace bsg::algos {
namespace {

constexpr double kLimit = 25.0;  // d

PidLagrangianOptions gains(double kp, double ki, double kd) {
  PidLagrangianOptions options;
  options.proportional_gain = kp;
  options.integral_gain = ki;
  options.derivative_gain = kd;
  return options;
}

std::vector<double> lambdas(PidLagrangian& pid, const std::vector<double>& costs) {
  std::vector<double> out;
  for (double cost : costs) out.push_back(pid.update(cost, kLimit).lambda);
  return out;
}

std::string error_of(const PidLagrangianOptions& options) {
  try {
    PidLagrangian pid(0.0, options);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(PidLagrangian, ProportionalOnlyFollowsTheCurrentViolation) {
  PidLagrangian pid(0.0, gains(0.5, 0.0, 0.0));
  // Delta = 5, -5, 10, 0 -> lambda = max(0, 0.5 Delta) = 2.5, 0, 5, 0
  const std::vector<double> expected = {2.5, 0.0, 5.0, 0.0};
  EXPECT_EQ(lambdas(pid, {30.0, 20.0, 35.0, 25.0}), expected);
  EXPECT_EQ(pid.last_terms().proportional, 0.0);
  PidLagrangian again(0.0, gains(0.5, 0.0, 0.0));
  again.update(30.0, kLimit);
  EXPECT_EQ(again.update(20.0, kLimit).proportional, -2.5);  // the term is signed; lambda is clamped
}

TEST(PidLagrangian, IntegralOnlyIsClampedAtZeroWithoutWindUp) {
  PidLagrangian pid(0.2, gains(0.0, 0.1, 0.0));
  // I = 0.2 + 0.1 * 5 = 0.7; max(0, 0.7 - 1.5) = 0; max(0, 0 - 1.5) = 0; 0 + 1.5 = 1.5.
  // Without the clamp it would be 0.7, -0.8, -2.3, -0.8 (lambda 0.7, 0, 0, 0).
  const std::vector<double> got = lambdas(pid, {30.0, 10.0, 10.0, 40.0});
  ASSERT_EQ(got.size(), 4u);
  EXPECT_NEAR(got[0], 0.7, 1e-15);
  EXPECT_EQ(got[1], 0.0);
  EXPECT_EQ(got[2], 0.0);
  EXPECT_NEAR(got[3], 1.5, 1e-15);
  EXPECT_NEAR(pid.last_terms().integral, 1.5, 1e-15);
}

TEST(PidLagrangian, DerivativeComparesWithTheCostDelayEpochsAgoAndOnlyRises) {
  PidLagrangianOptions options = gains(0.0, 0.0, 1.0);
  options.derivative_delay = 2;
  PidLagrangian pid(0.0, options);
  // J = 10, 20, 15, 30, 30, 10 and J before epoch 1 = 0:
  // D_k = max(0, J_k - J_{k-2}) = 10 - 0, 20 - 0, 15 - 10, 30 - 20, 30 - 15, max(0, 10 - 30)
  const std::vector<double> expected = {10.0, 20.0, 5.0, 10.0, 15.0, 0.0};
  EXPECT_EQ(lambdas(pid, {10.0, 20.0, 15.0, 30.0, 30.0, 10.0}), expected);

  options.derivative_delay = 1;
  PidLagrangian one_epoch(0.0, options);
  // D_k = max(0, J_k - J_{k-1}) = 10, 10, 0, 15, 0, 0
  const std::vector<double> expected_one = {10.0, 10.0, 0.0, 15.0, 0.0, 0.0};
  EXPECT_EQ(lambdas(one_epoch, {10.0, 20.0, 15.0, 30.0, 30.0, 10.0}), expected_one);
}

TEST(PidLagrangian, EmaSmoothsTheProportionalAndDerivativeInputs) {
  PidLagrangianOptions p_options = gains(1.0, 0.0, 0.0);
  p_options.proportional_ema = 0.5;
  PidLagrangian p(0.0, p_options);
  // Delta = 10, 10, -10: Delta_ema = 0.5 * 0 + 0.5 * 10 = 5, 0.5 * 5 + 5 = 7.5, 3.75 - 5 = -1.25
  EXPECT_EQ(p.update(35.0, kLimit).lambda, 5.0);
  EXPECT_EQ(p.update(35.0, kLimit).lambda, 7.5);
  const PidTerms third = p.update(15.0, kLimit);
  EXPECT_EQ(third.proportional, -1.25);
  EXPECT_EQ(third.lambda, 0.0);

  PidLagrangianOptions d_options = gains(0.0, 0.0, 1.0);
  d_options.derivative_ema = 0.5;
  PidLagrangian d(0.0, d_options);
  // J = 20, 20, 20, 0: J_ema = 10, 15, 17.5, 8.75; D = 10 - 0, 15 - 10, 17.5 - 15, max(0, 8.75 - 17.5)
  const std::vector<double> expected = {10.0, 5.0, 2.5, 0.0};
  EXPECT_EQ(lambdas(d, {20.0, 20.0, 20.0, 0.0}), expected);
}

TEST(PidLagrangian, AllThreeTermsAddAndTheUpperBoundCaps) {
  PidLagrangianOptions options = gains(0.1, 0.05, 0.2);
  PidLagrangian pid(0.001, options);
  // J = 35: P = 0.1 * 10 = 1, I = 0.001 + 0.05 * 10 = 0.501, D = 0.2 * (35 - 0) = 7
  const PidTerms terms = pid.update(35.0, kLimit);
  EXPECT_NEAR(terms.proportional, 1.0, 1e-15);
  EXPECT_NEAR(terms.integral, 0.501, 1e-15);
  EXPECT_NEAR(terms.derivative, 7.0, 1e-15);
  EXPECT_NEAR(terms.lambda, 8.501, 1e-14);

  options.lambda_max = 3.0;
  PidLagrangian capped(0.001, options);
  EXPECT_EQ(capped.update(35.0, kLimit).lambda, 3.0);
  EXPECT_NEAR(capped.last_terms().integral, 0.501, 1e-15);  // the terms are not capped, lambda is
}

TEST(PidLagrangian, LambdaIsNeverNegativeNorAboveItsBound) {
  Rng rng(11);
  for (int trial = 0; trial < 20; ++trial) {
    PidLagrangianOptions options = gains(uniform(rng, 0.0, 2.0), uniform(rng, 0.0, 0.2), uniform(rng, 0.0, 2.0));
    options.derivative_delay = 1 + trial % 5;
    options.proportional_ema = uniform(rng, 0.0, 0.99);
    options.derivative_ema = uniform(rng, 0.0, 0.99);
    options.lambda_max = trial % 2 == 0 ? 0.0 : 4.0;
    PidLagrangian pid(uniform(rng, 0.0, 1.0), options);
    for (int epoch = 0; epoch < 200; ++epoch) {
      const PidTerms terms = pid.update(uniform(rng, 0.0, 60.0), kLimit);
      ASSERT_GE(terms.lambda, 0.0);
      ASSERT_GE(terms.integral, 0.0);
      ASSERT_GE(terms.derivative, 0.0);
      if (options.lambda_max > 0.0) {
        ASSERT_LE(terms.lambda, options.lambda_max);
      }
      const double sum = terms.proportional + terms.integral + terms.derivative;
      ASSERT_EQ(terms.lambda, options.lambda_max > 0.0 ? std::min(std::max(sum, 0.0), options.lambda_max)
                                                       : std::max(sum, 0.0));
    }
  }
}

TEST(PidLagrangian, IntegralAloneEqualsTheSgdRule) {
  // The SGD oracle of lagrange_multiplier_test: 0.001 + 0.01 * 5 = 0.051, then max(0, 0.051 - 0.15) = 0.
  LagrangeMultiplier pid(0.001, LambdaOptimizer::pid, 1.0, gains(0.0, 0.01, 0.0));
  EXPECT_NEAR(pid.update(30.0, kLimit), 0.051, 1e-15);
  EXPECT_EQ(pid.update(10.0, kLimit), 0.0);

  // And step for step, bit for bit, over a long random cost sequence (the
  // initial max(init, 1e-5) included).
  Rng rng(3);
  for (double init : {0.0, 0.001, 0.7}) {
    LagrangeMultiplier sgd(init, LambdaOptimizer::sgd, 0.05);
    PidLagrangianOptions options = gains(0.0, 0.05, 0.0);
    options.derivative_delay = 4;
    options.proportional_ema = 0.9;  // smoothing an unused input changes nothing
    LagrangeMultiplier integral(init, LambdaOptimizer::pid, 0.05, options);
    EXPECT_EQ(integral.value(), sgd.value());
    for (int epoch = 0; epoch < 300; ++epoch) {
      const double cost = uniform(rng, 0.0, 50.0);
      ASSERT_EQ(integral.update(cost, kLimit), sgd.update(cost, kLimit)) << "epoch " << epoch;
    }
  }
}

TEST(PidLagrangian, DiagnosticsNameTheThreeTerms) {
  LagrangeMultiplier pid(0.001, LambdaOptimizer::pid, 1.0, gains(0.1, 0.05, 0.2));
  const std::vector<std::string> names = {"LagrangeMultiplier", "PID/P", "PID/I", "PID/D"};
  EXPECT_EQ(pid.diagnostic_names(), names);
  pid.update(35.0, kLimit);
  const std::vector<NamedScalar> values = pid.diagnostics();
  ASSERT_EQ(values.size(), 4u);
  EXPECT_EQ(values[0].value, pid.value());
  EXPECT_NEAR(values[1].value, 1.0, 1e-15);
  EXPECT_NEAR(values[2].value, 0.501, 1e-15);
  EXPECT_NEAR(values[3].value, 7.0, 1e-15);
  const std::vector<std::string> sgd_names = {"LagrangeMultiplier"};
  EXPECT_EQ(LagrangeMultiplier(0.001, LambdaOptimizer::sgd, 0.05).diagnostic_names(), sgd_names);
}

TEST(PidLagrangian, ARestoredStateContinuesExactlyAsTheUninterruptedRun) {
  PidLagrangianOptions options = gains(0.3, 0.02, 0.5);
  options.derivative_delay = 3;
  options.proportional_ema = 0.6;
  options.derivative_ema = 0.8;
  Rng rng(7);
  std::vector<double> costs;
  for (int i = 0; i < 40; ++i) costs.push_back(uniform(rng, 0.0, 50.0));

  LagrangeMultiplier whole(0.001, LambdaOptimizer::pid, 1.0, options);
  LagrangeMultiplier first(0.001, LambdaOptimizer::pid, 1.0, options);
  for (int i = 0; i < 17; ++i) {
    whole.update(costs[i], kLimit);
    first.update(costs[i], kLimit);
  }
  const std::vector<NamedScalar> saved = first.state();
  ASSERT_EQ(saved.size(), 1u + 3u + 3u);  // lambda, I, Delta_ema, J_ema, 3 delayed J_ema
  EXPECT_EQ(saved[1].name, "pid_integral");
  EXPECT_EQ(saved[6].name, "pid_cost_d_history_2");

  LagrangeMultiplier resumed(0.5, LambdaOptimizer::pid, 1.0, options);
  resumed.restore_state(saved);
  EXPECT_EQ(resumed.state(), saved);
  EXPECT_EQ(resumed.value(), whole.value());
  bool any_difference_without_history = false;
  std::vector<NamedScalar> no_history = saved;  // same I and EMAs, but an empty delay queue
  for (std::size_t i = 4; i < no_history.size(); ++i) no_history[i].value = 0.0;
  LagrangeMultiplier forgetful(0.5, LambdaOptimizer::pid, 1.0, options);
  forgetful.restore_state(no_history);
  for (std::size_t i = 17; i < costs.size(); ++i) {
    const double expected = whole.update(costs[i], kLimit);
    ASSERT_EQ(resumed.update(costs[i], kLimit), expected) << "epoch " << i;
    ASSERT_EQ(resumed.diagnostics(), whole.diagnostics());
    if (forgetful.update(costs[i], kLimit) != expected) any_difference_without_history = true;
  }
  EXPECT_TRUE(any_difference_without_history) << "the delay queue must matter for this test to mean anything";
}

TEST(PidLagrangian, RestoreRejectsAStateOfAnotherShapeOrInvalidValues) {
  PidLagrangianOptions options = gains(0.1, 0.05, 0.1);
  options.derivative_delay = 3;
  LagrangeMultiplier pid(0.001, LambdaOptimizer::pid, 1.0, options);
  options.derivative_delay = 4;
  LagrangeMultiplier longer(0.001, LambdaOptimizer::pid, 1.0, options);
  LagrangeMultiplier sgd(0.001, LambdaOptimizer::sgd, 0.05);
  EXPECT_THROW(pid.restore_state(longer.state()), std::invalid_argument);
  EXPECT_THROW(pid.restore_state(sgd.state()), std::invalid_argument);
  EXPECT_THROW(sgd.restore_state(pid.state()), std::invalid_argument);
  std::vector<NamedScalar> negative = pid.state();
  negative[1].value = -1.0;  // pid_integral
  EXPECT_THROW(pid.restore_state(negative), std::invalid_argument);
  std::vector<NamedScalar> not_finite = pid.state();
  not_finite[5].value = std::nan("");
  EXPECT_THROW(pid.restore_state(not_finite), std::invalid_argument);
  EXPECT_EQ(pid.value(), 0.001);  // a rejected state changes nothing
}

TEST(PidLagrangian, BadOptionsAreRejectedNamingTheKey) {
  EXPECT_NE(error_of(gains(-0.1, 0.0, 0.0)).find("pid_kp"), std::string::npos);
  EXPECT_NE(error_of(gains(0.0, std::nan(""), 0.0)).find("pid_ki"), std::string::npos);
  EXPECT_NE(error_of(gains(0.0, 0.0, -1.0)).find("pid_kd"), std::string::npos);
  PidLagrangianOptions options;
  options.derivative_delay = 0;
  EXPECT_NE(error_of(options).find("pid_d_delay"), std::string::npos);
  options = {};
  options.proportional_ema = 1.0;
  EXPECT_NE(error_of(options).find("pid_delta_p_ema_alpha"), std::string::npos);
  options = {};
  options.derivative_ema = -0.1;
  EXPECT_NE(error_of(options).find("pid_delta_d_ema_alpha"), std::string::npos);
  options = {};
  options.lambda_max = -2.0;
  EXPECT_NE(error_of(options).find("pid_lambda_max"), std::string::npos);
  EXPECT_THROW(PidLagrangian(0.0, {}).update(std::nan(""), kLimit), std::invalid_argument);
}

}  // namespace
}  // namespace bsg::algos
