// The natural-gradient step shared by TRPO, TRPO-L, PDO, CPO and PCPO
// (docs/algorithms.md#natural-step): x = CG(F, g), q = x^T F x (one extra operator call) and
// alpha = sqrt(2 delta / (q + 1e-8)); the full step is alpha x.
#pragma once

#include <Eigen/Core>

#include "algos/trust_region/conjugate_gradient.h"

namespace bsg::algos {

struct NaturalGradientStep {
  Eigen::VectorXd direction;  // x = F^-1 g (approximately)
  double x_fisher_x = 0.0;    // q = x^T F x
  double step_size = 0.0;     // alpha = sqrt(2 delta / (q + 1e-8))
  Eigen::VectorXd full_step;  // Delta = alpha x
};

// alpha = sqrt(2 delta / (q + 1e-8)); throws on negative or non-finite input.
double trust_region_step_size(double x_fisher_x, double target_kl);

// Throws std::runtime_error if x is not finite or q < 0 (the original asserts).
NaturalGradientStep natural_gradient_step(const LinearOperator& fisher, const Eigen::Ref<const Eigen::VectorXd>& gradient,
                                          double target_kl, ConjugateGradientOptions cg_options = {});

}  // namespace bsg::algos
