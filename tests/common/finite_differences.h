// Central finite differences, the independent oracle for hand-written
// gradients and Jacobian-vector products in the core's tests.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <functional>

namespace bsg::testing {

// d f / d theta by central differences, f scalar.
inline Eigen::VectorXd finite_difference_gradient(const std::function<double(const Eigen::VectorXd&)>& f,
                                                  const Eigen::VectorXd& theta, double step = 1e-6) {
  Eigen::VectorXd gradient(theta.size());
  Eigen::VectorXd shifted = theta;
  for (Eigen::Index k = 0; k < theta.size(); ++k) {
    shifted[k] = theta[k] + step;
    const double plus = f(shifted);
    shifted[k] = theta[k] - step;
    const double minus = f(shifted);
    shifted[k] = theta[k];
    gradient[k] = (plus - minus) / (2.0 * step);
  }
  return gradient;
}

// (f(theta + h v) - f(theta - h v)) / 2h for a vector-valued f.
inline Eigen::MatrixXd finite_difference_directional(
    const std::function<Eigen::MatrixXd(const Eigen::VectorXd&)>& f, const Eigen::VectorXd& theta,
    const Eigen::VectorXd& direction, double step = 1e-6) {
  return (f(theta + step * direction) - f(theta - step * direction)) / (2.0 * step);
}

// ||a - b|| / max(||b||, floor): the relative error used by the gradient checks.
inline double relative_error(const Eigen::MatrixXd& actual, const Eigen::MatrixXd& expected, double floor = 1e-12) {
  return (actual - expected).norm() / std::max(expected.norm(), floor);
}

}  // namespace bsg::testing
