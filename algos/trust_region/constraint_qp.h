// The two small problems of CPO and PCPO with m constraints (docs/algorithms.md#several-constraints),
// solved exactly by enumerating the active sets (m is small: at most kMaxConstraints).
// Everything is expressed through the Gram quantities the conjugate gradient
// gives, in the metric H (the Fisher matrix F, or I for PCPO's L2 projection):
//   q = g^T H^-1 g,  r_i = g^T H^-1 b_i,  S_ij = b_i^T H^-1 b_j.
//
// 1. CPO's trust-region problem (Achiam et al. 2017, eq. 10 with m constraints)
//      max_x g^T x  s.t.  c_i + b_i^T x <= 0 (i = 1..m),  1/2 x^T H x <= delta
//    through its dual in (lambda, nu_1..nu_m): with x = H^-1 (g - B nu) / lambda,
//      D(lambda, nu) = (q - 2 r^T nu + nu^T S nu) / (2 lambda) + lambda delta - c^T nu,
//    minimised over lambda > 0, nu >= 0. The optimal lambda for a given nu is
//    sqrt(Q(nu) / (2 delta)), Q(nu) = q - 2 r^T nu + nu^T S nu, which leaves the convex
//    problem min_{nu >= 0} sqrt(2 delta Q(nu)) - c^T nu. On an active set F
//    (nu_i > 0 exactly for i in F) its stationarity reads S_FF nu_F = r_F + lambda c_F,
//    and substituting gives Q = A_F + lambda^2 C_F with A_F = q - r_F^T S_FF^-1 r_F,
//    C_F = c_F^T S_FF^-1 c_F, hence lambda = sqrt(A_F / (2 delta - C_F)). Every
//    minimiser is such a candidate for its own F, and a candidate that satisfies
//    the KKT conditions (nu_F >= 0, d/dnu_j >= 0 off F) is a minimiser of a convex
//    problem; so trying every F finds the optimum. With m = 1 this is the
//    closed form of CPO's cases 1-3 with the corrected sign of r (Q10).
//    The problem is infeasible when the H-smallest x satisfying every constraint
//    (problem 2 with y = 0) lies outside the trust region; the step then goes along
//    that point, scaled to the trust region's boundary: it reduces every violated
//    constraint, most along those violated most, and with m = 1 it is CPO's pure
//    cost-decrease step -sqrt(2 delta / s) H^-1 b.
//
// 2. The projection of PCPO (Yang et al. 2020, eq. 4 with m half-spaces)
//      min_x 1/2 (x - y)^T H (x - y)  s.t.  c_i + b_i^T x <= 0,
//    whose solution is x = y - H^-1 B mu with mu the minimiser of
//      1/2 mu^T S mu - v^T mu over mu >= 0,  v_i = c_i + b_i^T y
//    (the linearised violations at y), again by active sets:
//    mu_F = S_FF^-1 v_F, accepted if mu_F >= 0 and (S mu - v)_j >= 0 off F.
//    With m = 1 it is mu = max(0, v) / s.
#pragma once

#include <Eigen/Core>

#include "common/constraint_config.h"

namespace bsg::algos {

// The largest m these exact methods accept (2^m active sets).
inline constexpr int kMaxConstraints = kMaxConstraintCount;

// CPO's cases with m constraints (logged as cpo_optim_case; the m = 1 numbers
// of cpo.h mean the same where they exist).
enum class MultiCpoCase : int {
  infeasible_recovery = 0,     // no x in the trust region satisfies every constraint
  feasible_recovery = 1,       // some c_i >= 0, a feasible step exists
  constraint_cuts_region = 2,  // every c_i < 0, some constraint active at the optimum
  region_feasible = 3,         // every c_i < 0, no constraint active: the TRPO step
};

// Cases 2 and 3 start from a feasible policy (every c_i < 0): there the line
// search also asks the reward surrogate to improve.
constexpr bool starts_feasible(MultiCpoCase optim_case) {
  return optim_case == MultiCpoCase::constraint_cuts_region || optim_case == MultiCpoCase::region_feasible;
}

struct CpoDualSolution {
  MultiCpoCase optim_case = MultiCpoCase::region_feasible;
  double lambda = 0.0;       // lambda* (0 in the infeasible case)
  Eigen::VectorXd nu;        // nu* (m entries; the infeasible case: the recovery weights)
  // The step is (H^-1 g - sum_i nu_i H^-1 b_i) * direction_scale: 1 / lambda*
  // when feasible; in the infeasible case H^-1 g is left out (reward_weight 0).
  double reward_weight = 1.0;
  double direction_scale = 0.0;
};

// Solves problem 1 for the Gram quantities q, r (m), S (m x m, symmetric
// positive semi-definite), the violations c (m) and the trust-region size
// delta > 0. Throws std::invalid_argument on mismatched sizes, m = 0 or
// m > kMaxConstraints, non-finite inputs or delta <= 0.
CpoDualSolution solve_cpo_dual(double q, const Eigen::Ref<const Eigen::VectorXd>& r,
                               const Eigen::Ref<const Eigen::MatrixXd>& S, const Eigen::Ref<const Eigen::VectorXd>& c,
                               double delta);

// Solves problem 2's dual: the mu >= 0 minimising 1/2 mu^T S mu - v^T mu.
// Sets whose S_FF is singular (linearly dependent b_i) are skipped; one
// without them always holds an optimum. Throws like solve_cpo_dual.
Eigen::VectorXd nonnegative_projection_weights(const Eigen::Ref<const Eigen::MatrixXd>& S,
                                               const Eigen::Ref<const Eigen::VectorXd>& v);

}  // namespace bsg::algos
