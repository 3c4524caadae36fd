// The natural-gradient step (docs/algorithms.md#natural-step) on a small known Fisher matrix.
#include "algos/trust_region/natural_gradient.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace bsg::algos {
namespace {

TEST(NaturalGradientStep, StepHasSquaredFisherNormTwoDelta) {
  // Dynamic size: GCC 12 reports a false -Warray-bounds for a fixed 2x2
  // matrix times a dynamic vector under AVX.
  Eigen::MatrixXd fisher(2, 2);
  fisher << 2.0, 0.5, 0.5, 1.0;
  int calls = 0;
  const LinearOperator apply = [&](const Eigen::Ref<const Eigen::VectorXd>& v, Eigen::Ref<Eigen::VectorXd> out) {
    out = fisher * v;
    ++calls;
  };
  const Eigen::Vector2d gradient(1.0, -2.0);
  const double target_kl = 0.01;
  const auto step = natural_gradient_step(apply, gradient, target_kl);
  const Eigen::Vector2d exact = fisher.ldlt().solve(gradient);
  EXPECT_LT((step.direction - exact).norm() / exact.norm(), 1e-5);
  EXPECT_NEAR(step.x_fisher_x, step.direction.dot(fisher * step.direction), 1e-14);
  // alpha^2 x^T F x = 2 delta q / (q + 1e-8)
  const double q = step.x_fisher_x;
  EXPECT_NEAR(step.step_size * step.step_size * q, 2.0 * target_kl * q / (q + 1e-8), 1e-15);
  EXPECT_LT((step.full_step - step.step_size * step.direction).norm(), 1e-15);
  // The 1e-6 epsilons keep the residual above 1e-10, so CG runs all 10
  // iterations: 1 + 10 calls for the solve, one for q.
  EXPECT_EQ(calls, 1 + 10 + 1);
}

TEST(NaturalGradientStep, StepSizeFormulaAndBadInput) {
  EXPECT_NEAR(trust_region_step_size(2.0, 0.01), std::sqrt(0.02 / (2.0 + 1e-8)), 1e-16);
  EXPECT_THROW(trust_region_step_size(-1.0, 0.01), std::runtime_error);
  EXPECT_THROW(trust_region_step_size(std::numeric_limits<double>::quiet_NaN(), 0.01), std::runtime_error);
  EXPECT_THROW(trust_region_step_size(1.0, 0.0), std::invalid_argument);
  const LinearOperator nan_operator = [](const Eigen::Ref<const Eigen::VectorXd>&, Eigen::Ref<Eigen::VectorXd> out) {
    out.setConstant(std::numeric_limits<double>::quiet_NaN());
  };
  EXPECT_THROW(natural_gradient_step(nan_operator, Eigen::Vector2d(1.0, 0.0), 0.01), std::runtime_error);
}

}  // namespace
}  // namespace bsg::algos
