// Conjugate gradient (docs/algorithms.md#conjugate-gradient) against Eigen's dense solver and the
// original's oracles (docs/algorithms.md#test-oracles including the 1e-6 quirk Q9).
#include "algos/trust_region/conjugate_gradient.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <stdexcept>

#include "common/random.h"

namespace bsg::algos {
namespace {

LinearOperator matrix_operator(const Eigen::MatrixXd& matrix, int* calls = nullptr) {
  return [matrix, calls](const Eigen::Ref<const Eigen::VectorXd>& v, Eigen::Ref<Eigen::VectorXd> out) {
    out = matrix * v;
    if (calls) ++*calls;
  };
}

TEST(ConjugateGradient, TwoByTwoOracleFromTheOriginalTests) {
  Eigen::Matrix2d a;
  a << 4, 1, 1, 3;
  const auto result = conjugate_gradient(matrix_operator(a), Eigen::Vector2d(1, 2), {.iterations = 15});
  // numpy allclose defaults: |x - y| <= 1e-8 + 1e-5 |y|
  EXPECT_NEAR(result.solution[0], 0.0909091, 1e-8 + 1e-5 * 0.0909091);
  EXPECT_NEAR(result.solution[1], 0.6363636, 1e-8 + 1e-5 * 0.6363636);
  EXPECT_NEAR(result.solution[0], 0.0909093, 5e-7);  // the epsilons shift it slightly
  EXPECT_NEAR(result.solution[1], 0.6363635, 5e-7);
}

TEST(ConjugateGradient, DiagonallyDominant150SystemOracle) {
  Rng rng(0);
  Eigen::MatrixXd u(150, 150);
  for (Eigen::Index i = 0; i < u.size(); ++i) u.data()[i] = uniform(rng, -1.0, 1.0);
  const Eigen::MatrixXd a = 0.5 * (u + u.transpose()) + 150.0 * Eigen::MatrixXd::Identity(150, 150);
  Eigen::VectorXd y(150);
  for (Eigen::Index i = 0; i < 150; ++i) y[i] = uniform(rng, 0.0, 0.01);
  const auto result = conjugate_gradient(matrix_operator(a), y, {.iterations = 25});
  const Eigen::VectorXd direct = a.ldlt().solve(y);
  EXPECT_LT((result.solution - direct).cwiseAbs().maxCoeff(), 1e-5);
}

struct SpdSystem {
  Eigen::MatrixXd matrix;
  Eigen::VectorXd rhs;
};

// A random n x n SPD matrix with eigenvalues in [0.5, 2] and a unit right-hand side.
SpdSystem random_spd_system(int n, Rng& rng) {
  Eigen::MatrixXd q(n, n);
  for (Eigen::Index i = 0; i < q.size(); ++i) q.data()[i] = standard_normal(rng);
  const Eigen::MatrixXd orthogonal = q.householderQr().householderQ();
  Eigen::VectorXd eigenvalues(n);
  for (int i = 0; i < n; ++i) eigenvalues[i] = uniform(rng, 0.5, 2.0);
  SpdSystem system{orthogonal * eigenvalues.asDiagonal() * orthogonal.transpose(), Eigen::VectorXd(n)};
  for (int i = 0; i < n; ++i) system.rhs[i] = standard_normal(rng);
  system.rhs /= system.rhs.norm();
  return system;
}

TEST(ConjugateGradient, WithoutEpsilonsSolvesRandomSpdSystemsLikeEigenDenseSolver) {
  Rng rng(1);
  for (int trial = 0; trial < 20; ++trial) {
    const int n = 2 + trial % 9;  // n <= 10
    const SpdSystem system = random_spd_system(n, rng);
    const Eigen::VectorXd direct = system.matrix.ldlt().solve(system.rhs);
    const auto result = conjugate_gradient(matrix_operator(system.matrix), system.rhs,
                                           {.iterations = 2 * n, .denominator_epsilon = 0.0});
    EXPECT_LT((result.solution - direct).norm() / direct.norm(), 1e-10) << "n = " << n;
  }
}

TEST(ConjugateGradient, EpsilonsLimitTheAccuracyOnWellScaledSpdSystems) {
  // With the original's 1e-6 (Q9) the step lengths shrink once r^T r nears 1e-6:
  // for unit right-hand sides the error stalls near 1e-4, whatever the iteration
  // count; 100 times larger right-hand sides reach about 1e-6.
  Rng rng(1);
  for (int trial = 0; trial < 20; ++trial) {
    const int n = 2 + trial % 9;
    const SpdSystem system = random_spd_system(n, rng);
    const Eigen::VectorXd direct = system.matrix.ldlt().solve(system.rhs);
    const auto unit = conjugate_gradient(matrix_operator(system.matrix), system.rhs, {.iterations = 10});
    const double unit_error = (unit.solution - direct).norm() / direct.norm();
    EXPECT_LT(unit_error, 1e-3) << "n = " << n;
    EXPECT_GT(unit_error, 1e-7) << "n = " << n << ": the epsilons must be visible";
    const auto longer = conjugate_gradient(matrix_operator(system.matrix), system.rhs, {.iterations = 40});
    EXPECT_GT((longer.solution - direct).norm() / direct.norm(), 1e-8) << "more iterations do not remove it";
    const auto scaled = conjugate_gradient(matrix_operator(system.matrix), 100.0 * system.rhs, {.iterations = 10});
    EXPECT_LT((scaled.solution - 100.0 * direct).norm() / (100.0 * direct.norm()), 1e-5) << "n = " << n;
  }
}

TEST(ConjugateGradient, EpsilonQuirkShrinksSmallGradientSolutions) {
  // docs/algorithms.md#test-oracles (Q9): F = 1e-3 I, y = (1e-3, 0), 10 iterations -> x_1 = 0.0174121 (exact: 1).
  const auto small = conjugate_gradient(matrix_operator(1e-3 * Eigen::Matrix2d::Identity()),
                                        Eigen::Vector2d(1e-3, 0.0));
  EXPECT_NEAR(small.solution[0], 0.0174121, 5e-8);
  EXPECT_EQ(small.solution[1], 0.0);
  const auto unit = conjugate_gradient(matrix_operator(Eigen::Matrix2d::Identity()), Eigen::Vector2d(1.0, 0.0));
  EXPECT_NEAR(unit.solution[0], 0.9999990, 5e-8);
}

TEST(ConjugateGradient, MakesOneOperatorCallMoreThanIterations) {
  int calls = 0;
  Eigen::Matrix3d a;
  a << 3, 1, 0, 1, 4, 1, 0, 1, 5;
  // A badly scaled right-hand side never meets the 1e-10 residual test within 10 iterations.
  const auto result = conjugate_gradient(matrix_operator(a, &calls), Eigen::Vector3d(1e-3, 2e-3, -1e-3));
  EXPECT_EQ(result.iterations, 10);
  EXPECT_EQ(result.operator_calls, 11);
  EXPECT_EQ(calls, 11);
}

TEST(ConjugateGradient, StopsEarlyWhenTheResidualVanishes) {
  int calls = 0;
  const auto result =
      conjugate_gradient(matrix_operator(Eigen::Matrix2d::Identity(), &calls), Eigen::Vector2d(0.0, 0.0));
  EXPECT_EQ(result.iterations, 1);
  EXPECT_EQ(calls, 2);
  EXPECT_EQ(result.solution, Eigen::Vector2d::Zero());
}

TEST(ConjugateGradient, BadInputGivesExceptions) {
  EXPECT_THROW(conjugate_gradient(LinearOperator{}, Eigen::Vector2d(1, 0)), std::invalid_argument);
  EXPECT_THROW(conjugate_gradient(matrix_operator(Eigen::Matrix2d::Identity()), Eigen::VectorXd(0)),
               std::invalid_argument);
  EXPECT_THROW(conjugate_gradient(matrix_operator(Eigen::Matrix2d::Identity()), Eigen::Vector2d(1, 0),
                                  {.iterations = -1}),
               std::invalid_argument);
}

}  // namespace
}  // namespace bsg::algos
