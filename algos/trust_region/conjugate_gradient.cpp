#include "algos/trust_region/conjugate_gradient.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace bsg::algos {

ConjugateGradientResult conjugate_gradient(const LinearOperator& apply_matrix,
                                           const Eigen::Ref<const Eigen::VectorXd>& rhs,
                                           ConjugateGradientOptions options) {
  if (!apply_matrix) throw std::invalid_argument("conjugate_gradient: apply_matrix is empty");
  if (options.iterations < 0) {
    throw std::invalid_argument("conjugate_gradient: iterations must be >= 0, got " +
                                std::to_string(options.iterations));
  }
  if (rhs.size() == 0) throw std::invalid_argument("conjugate_gradient: rhs is empty");
  const double eps = options.denominator_epsilon;
  ConjugateGradientResult result;
  Eigen::VectorXd& x = result.solution;
  x.setZero(rhs.size());                 // x_0 = 0
  Eigen::VectorXd z(rhs.size());
  apply_matrix(x, z);                    // F x_0 (an operator call that returns zeros)
  ++result.operator_calls;
  Eigen::VectorXd r = rhs - z;           // r = y - F x_0
  Eigen::VectorXd p = r;                 // p = r
  double rho = r.squaredNorm();          // rho = r^T r
  for (int i = 0; i < options.iterations; ++i) {
    apply_matrix(p, z);                  // z = F p
    ++result.operator_calls;
    ++result.iterations;
    const double alpha = rho / (p.dot(z) + eps);  // alpha = rho / (p^T z + 1e-6)
    x += alpha * p;
    r -= alpha * z;
    const double rho_new = r.squaredNorm();
    if (std::sqrt(rho_new) < options.residual_tolerance) break;
    const double beta = rho_new / (rho + eps);    // beta = rho' / (rho + 1e-6)
    p = r + beta * p;
    rho = rho_new;
  }
  return result;
}

}  // namespace bsg::algos
