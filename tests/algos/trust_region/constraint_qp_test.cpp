// CPO's dual and PCPO's projection with several constraints (algos/trust_region/constraint_qp.h,
// docs/algorithms.md#several-constraints) against independent oracles: closed forms for a
// diagonal metric with axis-aligned constraints, a brute-force search over a fine
// grid, the KKT conditions of the primal problem, each case (both constraints
// active, one, none, infeasible), and m = 1 against CPO's closed form (cpo.h).
#include "algos/trust_region/constraint_qp.h"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <cmath>
#include <initializer_list>
#include <limits>

#include "../algorithm_test_support.h"
#include "algos/trust_region/cpo.h"

namespace bsg::algos {
namespace {

// Dynamic-size vectors only: GCC 12 warns (-Warray-bounds) on Eigen's fixed-size temporaries here.
Eigen::VectorXd dvec(std::initializer_list<double> values) {
  Eigen::VectorXd v(static_cast<Eigen::Index>(values.size()));
  Eigen::Index i = 0;
  for (double x : values) v[i++] = x;
  return v;
}

// The primal problem max g^T x s.t. c_i + b_i^T x <= 0, 1/2 x^T H x <= delta, given densely.
struct TrustRegionProblem {
  Eigen::MatrixXd H;
  Eigen::VectorXd g;
  Eigen::MatrixXd B;  // columns b_i
  Eigen::VectorXd c;
  double delta = 0.5;
};

struct DualStep {
  CpoDualSolution dual;
  Eigen::VectorXd x;
};

// The Gram quantities through H^-1 (exact, not CG), the dual, and the step it gives.
DualStep solve(const TrustRegionProblem& p) {
  const Eigen::LDLT<Eigen::MatrixXd> H(p.H);
  const Eigen::VectorXd Hg = H.solve(p.g);
  const Eigen::MatrixXd HB = H.solve(p.B);
  const Eigen::VectorXd r = p.B.transpose() * Hg;
  const Eigen::MatrixXd S = p.B.transpose() * HB;
  DualStep out;
  out.dual = solve_cpo_dual(p.g.dot(Hg), r, S, p.c, p.delta);
  out.x = out.dual.direction_scale * (out.dual.reward_weight * Hg - HB * out.dual.nu);
  return out;
}

// Brute force over x_1, x_2 in the trust ellipse (grid spacing h); H diagonal,
// g_3 > 0, so the optimum has x_3 = +sqrt((2 delta - h1 x1^2 - h2 x2^2) / h3).
struct GridOptimum {
  double objective = -std::numeric_limits<double>::infinity();
  Eigen::VectorXd x = Eigen::VectorXd::Zero(3);
};
GridOptimum brute_force_three_dimensional(const TrustRegionProblem& p, int points) {
  const double h1 = p.H(0, 0), h2 = p.H(1, 1), h3 = p.H(2, 2);
  const double R1 = std::sqrt(2 * p.delta / h1), R2 = std::sqrt(2 * p.delta / h2);
  GridOptimum best;
  for (int i = 0; i <= points; ++i) {
    const double x1 = -R1 + 2 * R1 * i / points;
    for (int j = 0; j <= points; ++j) {
      const double x2 = -R2 + 2 * R2 * j / points;
      const double rest = 2 * p.delta - h1 * x1 * x1 - h2 * x2 * x2;
      if (rest < 0) continue;
      const Eigen::VectorXd x = dvec({x1, x2, std::sqrt(rest / h3)});
      if (((p.B.transpose() * x + p.c).array() > 0).any()) continue;
      const double objective = p.g.dot(x);
      if (objective > best.objective) best = {objective, x};
    }
  }
  return best;
}

// KKT of the primal: g = lambda H x + B nu, nu >= 0, lambda >= 0, feasibility, complementary slackness.
void expect_kkt(const TrustRegionProblem& p, const DualStep& s, double tolerance) {
  const Eigen::VectorXd residual = p.g - s.dual.lambda * p.H * s.x - p.B * s.dual.nu;
  EXPECT_LT(residual.norm(), tolerance) << "stationarity";
  EXPECT_GE(s.dual.nu.minCoeff(), 0.0);
  const Eigen::VectorXd slack = p.c + p.B.transpose() * s.x;
  EXPECT_LT(slack.maxCoeff(), tolerance) << "feasibility";
  EXPECT_LT(0.5 * s.x.dot(p.H * s.x) - p.delta, tolerance) << "trust region";
  for (Eigen::Index i = 0; i < p.c.size(); ++i) EXPECT_LT(std::abs(s.dual.nu[i] * slack[i]), tolerance);
  EXPECT_LT(std::abs(s.dual.lambda * (0.5 * s.x.dot(p.H * s.x) - p.delta)), tolerance);
}

// H = diag(1, 2, 4), g = (1, 1, 1), b_1 = e_1, b_2 = e_2: the constraints are x_1 <= -c_1, x_2 <= -c_2.
TrustRegionProblem axis_problem(double c1, double c2) {
  TrustRegionProblem p;
  p.H = dvec({1.0, 2.0, 4.0}).asDiagonal();
  p.g = dvec({1.0, 1.0, 1.0});
  p.B = Eigen::MatrixXd::Zero(3, 2);
  p.B(0, 0) = 1.0;
  p.B(1, 1) = 1.0;
  p.c = dvec({c1, c2});
  p.delta = 0.5;
  return p;
}

// Closed form for axis_problem: coordinates on the active set are pinned at
// t_i = -c_i; the free ones are g_j / (lambda h_j) with lambda spending the rest of the budget.
Eigen::VectorXd axis_closed_form(const TrustRegionProblem& p, bool pin1, bool pin2) {
  const Eigen::VectorXd h = p.H.diagonal();
  Eigen::VectorXd x = Eigen::VectorXd::Zero(3);
  double budget = 2 * p.delta;  // x^T H x <= 2 delta
  double free_norm = 0.0;       // sum g_j^2 / h_j over free j
  const bool pinned[3] = {pin1, pin2, false};
  for (int i = 0; i < 3; ++i) {
    if (pinned[i]) {
      x[i] = -p.c[i];
      budget -= h[i] * x[i] * x[i];
    } else {
      free_norm += p.g[i] * p.g[i] / h[i];
    }
  }
  const double lambda = std::sqrt(free_norm / budget);
  for (int i = 0; i < 3; ++i) {
    if (!pinned[i]) x[i] = p.g[i] / (lambda * h[i]);
  }
  return x;
}

TEST(CpoDual, NoConstraintActiveIsTheTrpoStep) {
  const TrustRegionProblem p = axis_problem(-2.0, -2.0);  // x_1 <= 2, x_2 <= 2: far away
  const DualStep s = solve(p);
  EXPECT_EQ(s.dual.optim_case, MultiCpoCase::region_feasible);
  EXPECT_EQ(s.dual.nu, Eigen::VectorXd::Zero(2));
  const Eigen::VectorXd expected = axis_closed_form(p, false, false);  // (0.7559, 0.3780, 0.1890)
  EXPECT_LT((s.x - expected).norm(), 1e-7);
  expect_kkt(p, s, 1e-7);
}

TEST(CpoDual, OneConstraintActive) {
  const TrustRegionProblem p = axis_problem(-0.3, -2.0);  // the TRPO step has x_1 = 0.756 > 0.3
  const DualStep s = solve(p);
  EXPECT_EQ(s.dual.optim_case, MultiCpoCase::constraint_cuts_region);
  EXPECT_GT(s.dual.nu[0], 0.0);
  EXPECT_EQ(s.dual.nu[1], 0.0);
  EXPECT_LT((s.x - axis_closed_form(p, true, false)).norm(), 1e-7);
  expect_kkt(p, s, 1e-7);
  const GridOptimum grid = brute_force_three_dimensional(p, 2000);
  EXPECT_NEAR(p.g.dot(s.x), grid.objective, 2e-3);
  EXPECT_GE(p.g.dot(s.x), grid.objective - 1e-7);  // no grid point beats the solution
  EXPECT_LT((s.x - grid.x).norm(), 5e-2);
}

TEST(CpoDual, BothConstraintsActive) {
  const TrustRegionProblem p = axis_problem(-0.3, -0.1);
  const DualStep s = solve(p);
  EXPECT_EQ(s.dual.optim_case, MultiCpoCase::constraint_cuts_region);
  EXPECT_GT(s.dual.nu[0], 0.0);
  EXPECT_GT(s.dual.nu[1], 0.0);
  const Eigen::VectorXd expected = axis_closed_form(p, true, true);  // (0.3, 0.1, sqrt((1 - 0.09 - 0.02) / 4))
  EXPECT_NEAR(expected[2], std::sqrt(0.89 / 4.0), 1e-15);
  EXPECT_LT((s.x - expected).norm(), 1e-7);
  expect_kkt(p, s, 1e-7);
  // nu_i = g_i - lambda h_i x_i with lambda = g_3 / (h_3 x_3).
  const double lambda = 1.0 / (4.0 * expected[2]);
  EXPECT_NEAR(s.dual.lambda, lambda, 1e-7);
  EXPECT_NEAR(s.dual.nu[0], 1.0 - lambda * 1.0 * 0.3, 1e-7);
  EXPECT_NEAR(s.dual.nu[1], 1.0 - lambda * 2.0 * 0.1, 1e-7);
  const GridOptimum grid = brute_force_three_dimensional(p, 2000);
  EXPECT_NEAR(p.g.dot(s.x), grid.objective, 2e-3);
  EXPECT_GE(p.g.dot(s.x), grid.objective - 1e-7);
}

TEST(CpoDual, ViolatedButRecoverableConstraint) {
  // c_1 = +0.2: the current policy violates constraint 1 (x_1 <= -0.2 needed), a feasible step exists.
  const TrustRegionProblem p = axis_problem(0.2, -2.0);
  const DualStep s = solve(p);
  EXPECT_EQ(s.dual.optim_case, MultiCpoCase::feasible_recovery);
  EXPECT_LT((s.x - axis_closed_form(p, true, false)).norm(), 1e-7);
  EXPECT_NEAR(s.x[0], -0.2, 1e-7);  // the step divides by lambda* + 1e-8 (CPO's epsilon)
  expect_kkt(p, s, 1e-7);
  const GridOptimum grid = brute_force_three_dimensional(p, 2000);
  EXPECT_NEAR(p.g.dot(s.x), grid.objective, 2e-3);
  EXPECT_GE(p.g.dot(s.x), grid.objective - 1e-7);
}

TEST(CpoDual, InfeasibleRecoversAlongTheViolatedConstraints) {
  // x_1 <= -0.8 and x_2 <= -0.6 need 1/2 (0.64 + 2 0.36) = 0.68 > delta = 0.5: infeasible.
  const TrustRegionProblem p = axis_problem(0.8, 0.6);
  EXPECT_LT(brute_force_three_dimensional(p, 400).objective, -1e300);  // no grid point is feasible
  const DualStep s = solve(p);
  EXPECT_EQ(s.dual.optim_case, MultiCpoCase::infeasible_recovery);
  EXPECT_EQ(s.dual.lambda, 0.0);
  // The H-smallest point of the intersection is (-0.8, -0.6, 0); the step is it scaled to the boundary.
  const Eigen::VectorXd smallest = dvec({-0.8, -0.6, 0.0});
  const Eigen::VectorXd expected = smallest * std::sqrt(0.5 / 0.68);
  EXPECT_LT((s.x - expected).norm(), 1e-9);
  EXPECT_NEAR(0.5 * s.x.dot(p.H * s.x), p.delta, 1e-12);
}

TEST(CpoDual, InfeasibleWithOneViolatedConstraintIgnoresTheSatisfiedOne) {
  // x_1 <= -1.2 alone needs 1/2 1.44 > 0.5; constraint 2 (x_2 <= 2) is slack and gets weight 0.
  const TrustRegionProblem p = axis_problem(1.2, -2.0);
  const DualStep s = solve(p);
  EXPECT_EQ(s.dual.optim_case, MultiCpoCase::infeasible_recovery);
  EXPECT_EQ(s.dual.nu[1], 0.0);
  EXPECT_LT((s.x - dvec({-1.0, 0.0, 0.0})).norm(), 1e-9);  // -sqrt(2 delta / s) e_1
}

TEST(CpoDual, OneConstraintMatchesCposClosedFormWithTheCorrectedSign) {
  Rng rng(5);
  const Eigen::MatrixXd fisher = testing::random_spd(6, rng);
  Eigen::VectorXd g(6), b(6);
  for (int i = 0; i < 6; ++i) {
    g[i] = standard_normal(rng);
    b[i] = standard_normal(rng);
  }
  for (double c : {-0.05, -0.001, 0.002, 0.05, 0.5}) {
    CpoStepOptions options;
    options.target_kl = 0.01;
    options.r_sign = CpoRSign::corrected;
    options.conjugate_gradient.iterations = 50;
    const CpoStep closed = cpo_step(testing::dense_operator(fisher), g, b, c, options);
    TrustRegionProblem p;
    p.H = fisher;
    p.g = g;
    p.B = b;
    p.c = Eigen::VectorXd::Constant(1, c);
    p.delta = 0.01;
    const DualStep s = solve(p);
    EXPECT_EQ(s.dual.optim_case == MultiCpoCase::infeasible_recovery,
              closed.optim_case == CpoCase::infeasible_recovery)
        << "c = " << c;
    // cpo_step solves with CG and adds 1e-8 to s and lambda*; the oracle here uses an exact solve.
    EXPECT_LT((s.x - closed.full_step).norm(), 2e-4 * closed.full_step.norm()) << "c = " << c;
  }
}

TEST(CpoDual, KktHoldsForThreeConstraintsInAGeneralMetric) {
  Rng rng(17);
  for (int trial = 0; trial < 20; ++trial) {
    TrustRegionProblem p;
    p.H = testing::random_spd(7, rng);
    p.g.resize(7);
    p.B.resize(7, 3);
    for (int i = 0; i < 7; ++i) {
      p.g[i] = standard_normal(rng);
      for (int j = 0; j < 3; ++j) p.B(i, j) = standard_normal(rng);
    }
    p.c = dvec({0.3 * standard_normal(rng), 0.3 * standard_normal(rng), 0.3 * standard_normal(rng)});
    p.delta = 0.05;
    const DualStep s = solve(p);
    if (s.dual.optim_case == MultiCpoCase::infeasible_recovery) continue;
    expect_kkt(p, s, 1e-8);
  }
}

TEST(CpoDual, RejectsBadInput) {
  EXPECT_THROW(solve_cpo_dual(1.0, Eigen::VectorXd(0), Eigen::MatrixXd(0, 0), Eigen::VectorXd(0), 0.1),
               std::invalid_argument);
  EXPECT_THROW(solve_cpo_dual(1.0, dvec({0, 0}), Eigen::MatrixXd::Identity(2, 2), dvec({0, 0}), 0.0),
               std::invalid_argument);
  EXPECT_THROW(solve_cpo_dual(1.0, dvec({0, 0}), Eigen::MatrixXd::Identity(3, 3), dvec({0, 0}), 0.1),
               std::invalid_argument);
}

// PCPO: min 1/2 (x - y)^T H (x - y) s.t. c + B^T x <= 0 is x = y - H^-1 B mu.
Eigen::VectorXd project(const Eigen::MatrixXd& H, const Eigen::MatrixXd& B, const Eigen::VectorXd& c,
                        const Eigen::VectorXd& y) {
  const Eigen::LDLT<Eigen::MatrixXd> solver(H);
  const Eigen::MatrixXd HB = solver.solve(B);
  const Eigen::VectorXd v = c + B.transpose() * y;
  return y - HB * nonnegative_projection_weights(B.transpose() * HB, v);
}

TEST(PcpoProjection, DiagonalMetricAndAxisConstraintsClampEachCoordinate) {
  const Eigen::MatrixXd H = dvec({1.0, 3.0, 0.5}).asDiagonal();
  Eigen::MatrixXd B = Eigen::MatrixXd::Zero(3, 2);
  B(0, 0) = 1.0;
  B(1, 1) = 1.0;
  const Eigen::VectorXd c = dvec({-0.2, -0.4});  // x_1 <= 0.2, x_2 <= 0.4
  for (const Eigen::VectorXd& y : {dvec({0.5, 0.9, 1.0}), dvec({0.1, 0.9, -1.0}),
                                   dvec({0.5, 0.1, 2.0}), dvec({0.1, 0.3, 0.0})}) {
    const Eigen::VectorXd expected = dvec({std::min(y[0], 0.2), std::min(y[1], 0.4), y[2]});
    EXPECT_LT((project(H, B, c, y) - expected).norm(), 1e-12);
  }
}

TEST(PcpoProjection, MatchesBruteForceInTheFisherMetric) {
  Eigen::MatrixXd H(2, 2);
  H << 2.0, 1.0, 1.0, 2.0;
  Eigen::MatrixXd B(2, 2);
  B << 1.0, 0.3, 0.0, 1.0;  // b_1 = (1, 0), b_2 = (0.3, 1)
  const Eigen::VectorXd c = dvec({-0.1, -0.2});
  for (const Eigen::VectorXd& y : {dvec({0.6, 0.6}), dvec({0.5, -0.4}), dvec({-0.5, 0.7}),
                                   dvec({-0.3, -0.3})}) {
    const Eigen::VectorXd x = project(H, B, c, y);
    double best = std::numeric_limits<double>::infinity();
    Eigen::VectorXd best_x = Eigen::VectorXd::Zero(2);
    constexpr int kPoints = 1500;
    for (int i = 0; i <= kPoints; ++i) {
      for (int j = 0; j <= kPoints; ++j) {
        const Eigen::VectorXd z = dvec({-1.5 + 3.0 * i / kPoints, -1.5 + 3.0 * j / kPoints});
        if (((B.transpose() * z + c).array() > 0).any()) continue;
        // Named vectors: GCC 12 misreads Eigen's SSE2 dot of an inline product as reading past a
        // 16-byte temporary (a false -Warray-bounds in BSG_NATIVE=OFF builds).
        const Eigen::VectorXd step = z - y;
        const Eigen::VectorXd curvature = H * step;
        const double distance = 0.5 * step.dot(curvature);
        if (distance < best) {
          best = distance;
          best_x = z;
        }
      }
    }
    const double distance = 0.5 * (x - y).dot(H * (x - y));
    EXPECT_LE(distance, best + 1e-12);   // nothing on the grid is closer
    EXPECT_NEAR(distance, best, 5e-3);   // and the grid gets close to it
    EXPECT_LT((x - best_x).norm(), 1e-2);
    EXPECT_LT((B.transpose() * x + c).maxCoeff(), 1e-12);
  }
}

TEST(PcpoProjection, OneConstraintIsMaxZeroVOverS) {
  const Eigen::MatrixXd S = Eigen::MatrixXd::Constant(1, 1, 2.5);
  EXPECT_NEAR(nonnegative_projection_weights(S, Eigen::VectorXd::Constant(1, 0.5))[0], 0.2, 1e-15);
  EXPECT_EQ(nonnegative_projection_weights(S, Eigen::VectorXd::Constant(1, -0.5))[0], 0.0);
}

TEST(PcpoProjection, DependentGradientsStillProject) {
  // b_2 = 2 b_1: S is singular; the projection onto x_1 <= 0.1 (the tighter of x_1 <= 0.1, 2 x_1 <= 0.4).
  const Eigen::MatrixXd H = Eigen::MatrixXd::Identity(2, 2);
  Eigen::MatrixXd B(2, 2);
  B << 1.0, 2.0, 0.0, 0.0;
  const Eigen::VectorXd x = project(H, B, dvec({-0.1, -0.4}), dvec({0.7, 0.3}));
  EXPECT_LT((x - dvec({0.1, 0.3})).norm(), 1e-12);
}

}  // namespace
}  // namespace bsg::algos
