#include "algos/trust_region/natural_gradient.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace bsg::algos {

double trust_region_step_size(double x_fisher_x, double target_kl) {
  if (!(target_kl > 0.0) || !std::isfinite(target_kl)) {
    throw std::invalid_argument("trust_region_step_size: target_kl must be positive, got " +
                                std::to_string(target_kl));
  }
  if (!(x_fisher_x >= 0.0) || !std::isfinite(x_fisher_x)) {
    throw std::runtime_error("trust_region_step_size: x^T F x must be finite and >= 0, got " +
                             std::to_string(x_fisher_x));
  }
  return std::sqrt(2.0 * target_kl / (x_fisher_x + 1e-8));  // alpha = sqrt(2 delta / (xHx + 1e-8))
}

NaturalGradientStep natural_gradient_step(const LinearOperator& fisher,
                                          const Eigen::Ref<const Eigen::VectorXd>& gradient, double target_kl,
                                          ConjugateGradientOptions cg_options) {
  NaturalGradientStep step;
  step.direction = conjugate_gradient(fisher, gradient, cg_options).solution;  // x = CG(F, g)
  if (!step.direction.allFinite()) {
    throw std::runtime_error("natural_gradient_step: the CG solution x is not finite (gradient norm " +
                             std::to_string(gradient.norm()) + ")");
  }
  Eigen::VectorXd fisher_x(gradient.size());
  fisher(step.direction, fisher_x);
  step.x_fisher_x = step.direction.dot(fisher_x);  // q = x^T F x
  step.step_size = trust_region_step_size(step.x_fisher_x, target_kl);
  step.full_step = step.step_size * step.direction;  // Delta = alpha x
  return step;
}

}  // namespace bsg::algos
