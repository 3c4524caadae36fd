// Adam with PyTorch's update rule, against steps worked out by hand.
#include "common/adam.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace bsg {
namespace {

TEST(Adam, FirstStepMovesEachParameterByLearningRateTimesSignOfGradient) {
  // t = 1: m_hat = g, v_hat = g^2, so the step is lr * g / (|g| + eps).
  Adam adam(2, AdamOptions{.learning_rate = 0.1});
  Eigen::VectorXd theta(2);
  theta << 1.0, -2.0;
  Eigen::VectorXd gradient(2);
  gradient << 4.0, -0.5;
  adam.step(theta, gradient);
  EXPECT_NEAR(theta[0], 1.0 - 0.1 * 4.0 / (4.0 + 1e-8), 1e-15);
  EXPECT_NEAR(theta[1], -2.0 + 0.1 * 0.5 / (0.5 + 1e-8), 1e-15);
  EXPECT_EQ(adam.step_count(), 1);
  EXPECT_NEAR(adam.first_moment()[0], 0.4, 1e-15);       // (1 - 0.9) g
  EXPECT_NEAR(adam.second_moment()[0], 0.016, 1e-15);    // (1 - 0.999) g^2
}

TEST(Adam, SecondStepMatchesHandComputation) {
  // g_1 = 1, g_2 = 3, lr = 0.01:
  // m_2 = 0.9*0.1 + 0.1*3 = 0.39;  v_2 = 0.999*0.001 + 0.001*9 = 0.009999
  // m_hat = 0.39/0.19;  v_hat = 0.009999/0.001999
  // step = 0.01 * m_hat / (sqrt(v_hat) + 1e-8)
  Adam adam(1, AdamOptions{.learning_rate = 0.01});
  Eigen::VectorXd theta = Eigen::VectorXd::Zero(1);
  adam.step(theta, Eigen::VectorXd::Constant(1, 1.0));
  const double after_first = -0.01 * 1.0 / (1.0 + 1e-8);
  EXPECT_NEAR(theta[0], after_first, 1e-16);
  adam.step(theta, Eigen::VectorXd::Constant(1, 3.0));
  const double m_hat = 0.39 / 0.19;
  const double v_hat = 0.009999 / 0.001999;
  EXPECT_NEAR(theta[0], after_first - 0.01 * m_hat / (std::sqrt(v_hat) + 1e-8), 1e-14);
}

TEST(Adam, PdoMultiplierOracle) {
  // docs/algorithms.md#pdo: lambda_0 = 0.001, lr = 0.001, J_C - d = 5 -> gradient -5 -> lambda_1 = 0.002.
  Adam adam(1, AdamOptions{.learning_rate = 0.001});
  Eigen::VectorXd lambda = Eigen::VectorXd::Constant(1, 0.001);
  adam.step(lambda, Eigen::VectorXd::Constant(1, -5.0));
  EXPECT_NEAR(lambda[0], 0.002, 1e-11);
}

TEST(Adam, ZeroGradientWithFreshStateLeavesParametersUnchanged) {
  Adam adam(3);
  Eigen::VectorXd theta = Eigen::VectorXd::LinSpaced(3, 1.0, 3.0);
  const Eigen::VectorXd before = theta;
  adam.step(theta, Eigen::VectorXd::Zero(3));
  EXPECT_EQ(theta, before);
}

TEST(Adam, StateRoundTripsThroughSetState) {
  Adam a(2), b(2);
  Eigen::VectorXd theta_a = Eigen::VectorXd::Ones(2);
  a.step(theta_a, Eigen::Vector2d(0.3, -0.7));
  b.set_state(a.first_moment(), a.second_moment(), a.step_count());
  Eigen::VectorXd theta_b = theta_a;
  a.step(theta_a, Eigen::Vector2d(0.1, 0.2));
  b.step(theta_b, Eigen::Vector2d(0.1, 0.2));
  EXPECT_EQ(theta_a, theta_b);
}

TEST(Adam, WrongSizesAndOptionsGiveExceptions) {
  EXPECT_THROW(Adam(0), std::invalid_argument);
  EXPECT_THROW(Adam(2, AdamOptions{.learning_rate = -1.0}), std::invalid_argument);
  EXPECT_THROW(Adam(2, AdamOptions{.beta1 = 1.0}), std::invalid_argument);
  Adam adam(2);
  Eigen::VectorXd theta = Eigen::VectorXd::Zero(2);
  try {
    adam.step(theta, Eigen::VectorXd::Zero(3));
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("gradient 3"), std::string::npos) << e.what();
  }
  EXPECT_THROW(adam.set_state(Eigen::VectorXd::Zero(1), Eigen::VectorXd::Zero(2), 0), std::invalid_argument);
  EXPECT_THROW(adam.set_state(Eigen::VectorXd::Zero(2), Eigen::VectorXd::Zero(2), -1), std::invalid_argument);
}

}  // namespace
}  // namespace bsg
