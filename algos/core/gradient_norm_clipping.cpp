#include "algos/core/gradient_norm_clipping.h"

#include <cmath>

namespace bsg::algos {

double clip_gradient_norm(std::span<Eigen::VectorXd* const> gradients, double max_norm) {
  double squared_norm = 0.0;
  for (const Eigen::VectorXd* gradient : gradients) squared_norm += gradient->squaredNorm();
  const double norm = std::sqrt(squared_norm);
  if (max_norm > 0.0 && norm > max_norm) {
    const double scale = max_norm / norm;
    for (Eigen::VectorXd* gradient : gradients) *gradient *= scale;
  }
  return norm;
}

double clip_gradient_norm(Eigen::VectorXd& gradient, double max_norm) {
  Eigen::VectorXd* const one[] = {&gradient};
  return clip_gradient_norm(one, max_norm);
}

}  // namespace bsg::algos
