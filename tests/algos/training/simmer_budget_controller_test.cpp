// SimmerBudgetController (algos/training/simmer_budget_controller.h): the budget step by step on
// a scripted cost sequence against a hand computation of OmniSafe's SimmerPIDAgent; the window of
// the integral term; the clips of the step and of the budget; a restored state continues alike.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "algos/training/simmer_budget_controller.h"

namespace bsg::algos {
namespace {

TEST(SimmerBudgetController, TheBudgetFollowsTheHandComputation) {
  // K_P = 0.5, K_I = 0.1, K_D = 0.2, p = 0.5, b_max = 10, b_0 = 4.
  SimmerBudgetController controller(SimmerControllerOptions{0.5, 0.1, 0.2, 0.5, 10.0, 4.0});
  EXPECT_EQ(controller.budget(), 4.0);
  // k = 0, J = 2: e = 0.5 * 0 + 0.5 (4 - 2) = 1, sum 1, u = 0.5 + 0.1 + 0.2 (0 - 0) = 0.6; b = 4.6, s = u = 0.6.
  EXPECT_NEAR(controller.step(2.0), 4.6, 1e-12);
  // k = 1, J = 8: e = 0.5 * 1 + 0.5 (4.6 - 8) = -1.2, sum -0.2,
  // u = -0.6 - 0.02 + 0.2 (0.6 - 0.6) = -0.62; b = 3.98, s = u = -0.62.
  EXPECT_NEAR(controller.step(8.0), 3.98, 1e-12);
  // k = 2, J = 30: e = -0.6 + 0.5 (3.98 - 30) = -13.61, sum -13.81,
  // u = -6.805 - 1.381 + 0.2 (-0.62 + 0.62) = -8.186, clipped to -1: b = 2.98, s = -1.
  EXPECT_NEAR(controller.step(30.0), 2.98, 1e-12);
  // k = 3, J = 0: e = 0.5 (-13.61) + 0.5 (2.98 - 0) = -5.315, sum -19.125,
  // u = -2.6575 - 1.9125 + 0.2 (-1 + 8.186) = -4.57 + 1.4372 = -3.1328, clipped: b = 1.98.
  EXPECT_NEAR(controller.step(0.0), 1.98, 1e-12);
  // Two more epochs at J = 100 step down by 1 each, the second to the floor 1e-6 (0.98 - 1 < 0).
  EXPECT_NEAR(controller.step(100.0), 0.98, 1e-12);
  EXPECT_EQ(controller.step(100.0), 1e-6);
}

TEST(SimmerBudgetController, TheCeilingHoldsAndTheDerivativeTermSeesTheClippedStep) {
  // K_P = 0.5, K_I = 0.1, K_D = 0.2, p = 0.5, b_max = 10, b_0 = 9.5; J = 0.
  SimmerBudgetController controller(SimmerControllerOptions{0.5, 0.1, 0.2, 0.5, 10.0, 9.5});
  // e = 0.5 * 9.5 = 4.75, u = 2.375 + 0.475 = 2.85 -> 1, b = min(10.5, 10) = 10; s = 0.5.
  EXPECT_EQ(controller.step(0.0), 10.0);
  // J = 20: e = 0.5 * 4.75 + 0.5 (10 - 20) = -2.625, sum 2.125,
  // u = -1.3125 + 0.2125 + 0.2 (0.5 - 2.85) = -1.57 -> -1; b = 9.
  EXPECT_NEAR(controller.step(20.0), 9.0, 1e-12);
  // J = 14: e = 0.5 (-2.625) + 0.5 (9 - 14) = -3.8125, sum -1.6875,
  // u = -1.90625 - 0.16875 + 0.2 (-1 - (-1.57)) = -2.075 + 0.114 = -1.961 -> -1; b = 8.
  EXPECT_NEAR(controller.step(14.0), 8.0, 1e-12);
}

TEST(SimmerBudgetController, TheIntegralSumsTheLastTenErrorsOnly) {
  // K_I = 1 alone, p = 0 (e_k = b_k - J_k), b_0 = 50 of 100. Errors 0.1 for ten epochs, then 0:
  // the steps are the window's sums 0.1, 0.2, ..., 1.0, then 0.9, 0.8, ..., 0 as the 0.1s leave it,
  // so b = 50 + 5.5 + 4.5 = 60 (an unbounded sum would keep stepping by 1: 65.5).
  SimmerBudgetController controller(SimmerControllerOptions{0.0, 1.0, 0.0, 0.0, 100.0, 50.0});
  for (int k = 0; k < 20; ++k) controller.step(controller.budget() - (k < 10 ? 0.1 : 0.0));
  EXPECT_NEAR(controller.budget(), 60.0, 1e-9);
}

TEST(SimmerBudgetController, ARestoredStateContinuesExactly) {
  const SimmerControllerOptions options{0.3, 0.2, 0.4, 0.7, 30.0, 12.0};
  const std::vector<double> costs = {3, 25, 40, 1, 7, 19, 2, 33, 8, 15, 0, 22, 11, 5};
  SimmerBudgetController whole(options);
  SimmerBudgetController first(options);
  for (std::size_t k = 0; k < 12; ++k) {
    whole.step(costs[k]);
    first.step(costs[k]);
  }
  SimmerBudgetController resumed(options);
  resumed.restore_state(first.state("c_"), "c_");
  EXPECT_EQ(resumed.state("c_"), first.state("c_"));
  for (std::size_t k = 12; k < costs.size(); ++k) EXPECT_EQ(resumed.step(costs[k]), whole.step(costs[k])) << k;
}

TEST(SimmerBudgetController, OptionsAndStatesItCannotUseAreRefused) {
  EXPECT_THROW(SimmerBudgetController(SimmerControllerOptions{-0.1, 0, 0, 0.5, 1, 1}), std::invalid_argument);
  EXPECT_THROW(SimmerBudgetController(SimmerControllerOptions{0, 0, 0, 1.0, 1, 1}), std::invalid_argument);
  EXPECT_THROW(SimmerBudgetController(SimmerControllerOptions{0, 0, 0, 0.5, 1, 0}), std::invalid_argument);
  EXPECT_THROW(SimmerBudgetController(SimmerControllerOptions{0, 0, 0, 0.5, 1, 1.5}), std::invalid_argument);
  SimmerBudgetController controller(SimmerControllerOptions{});
  EXPECT_THROW(controller.step(std::nan("")), std::invalid_argument);
  std::vector<NamedScalar> state = controller.state("a_");
  EXPECT_THROW(controller.restore_state(state, "b_"), std::invalid_argument);  // other names
  state[4].value = 11;                                                         // more errors than the window
  EXPECT_THROW(controller.restore_state(state, "a_"), std::invalid_argument);
}

}  // namespace
}  // namespace bsg::algos
