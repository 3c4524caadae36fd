// Conjugate gradient exactly as the original code (docs/algorithms.md#conjugate-gradient), including its
// 1e-6 added to both denominators (quirk Q9), which shrinks the solution when
// ||y||^2 is small against 1e-6. The first step computes r = y - F x_0 with
// x_0 = 0 by one real operator call, so that every rank makes the same
// sequence of collective calls: a solve makes 1 + iterations calls at most.
//
// Parameters:
//   iterations            10 (cg_iters)
//   denominator_epsilon   1e-6
//   residual_tolerance    1e-10 (stop when ||r|| < tolerance)
#pragma once

#include <Eigen/Core>
#include <functional>

namespace bsg::algos {

// product = A direction (A symmetric positive definite, e.g. the damped Fisher matrix).
using LinearOperator =
    std::function<void(const Eigen::Ref<const Eigen::VectorXd>& direction, Eigen::Ref<Eigen::VectorXd> product)>;

struct ConjugateGradientOptions {
  int iterations = 10;
  double denominator_epsilon = 1e-6;
  double residual_tolerance = 1e-10;
};

struct ConjugateGradientResult {
  Eigen::VectorXd solution;  // x
  int iterations = 0;        // iterations run
  int operator_calls = 0;    // 1 + iterations
};

ConjugateGradientResult conjugate_gradient(const LinearOperator& apply_matrix,
                                           const Eigen::Ref<const Eigen::VectorXd>& rhs,
                                           ConjugateGradientOptions options = {});

}  // namespace bsg::algos
