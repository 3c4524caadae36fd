#include "algos/trust_region/constraint_qp.h"

#include <Eigen/LU>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace bsg::algos {
namespace {

void check_sizes(const char* where, const Eigen::Ref<const Eigen::MatrixXd>& S,
                 const Eigen::Ref<const Eigen::VectorXd>& v) {
  const Eigen::Index m = v.size();
  if (m == 0 || m > kMaxConstraints) {
    throw std::invalid_argument(std::string(where) + ": the number of constraints must be 1.." +
                                std::to_string(kMaxConstraints) + ", got " + std::to_string(m));
  }
  if (S.rows() != m || S.cols() != m) {
    throw std::invalid_argument(std::string(where) + ": S is " + std::to_string(S.rows()) + " x " +
                                std::to_string(S.cols()) + ", expected " + std::to_string(m) + " x " +
                                std::to_string(m));
  }
  if (!S.allFinite() || !v.allFinite()) throw std::invalid_argument(std::string(where) + ": non-finite input");
}

// The indices of active set number `mask` (bit i set: constraint i is free).
std::vector<Eigen::Index> members(unsigned mask, Eigen::Index m) {
  std::vector<Eigen::Index> indices;
  for (Eigen::Index i = 0; i < m; ++i) {
    if ((mask >> i) & 1u) indices.push_back(i);
  }
  return indices;
}

// x_F = S_FF^-1 rhs_F spread into m entries (0 off F); false if S_FF is singular.
bool solve_on_set(const Eigen::Ref<const Eigen::MatrixXd>& S, const std::vector<Eigen::Index>& set,
                  const Eigen::VectorXd& rhs, Eigen::VectorXd& x) {
  const Eigen::Index k = static_cast<Eigen::Index>(set.size());
  x.setZero(S.rows());
  if (k == 0) return true;
  Eigen::MatrixXd S_FF(k, k);
  Eigen::VectorXd rhs_F(k);
  for (Eigen::Index a = 0; a < k; ++a) {
    rhs_F[a] = rhs[set[static_cast<std::size_t>(a)]];
    for (Eigen::Index b = 0; b < k; ++b) S_FF(a, b) = S(set[static_cast<std::size_t>(a)], set[static_cast<std::size_t>(b)]);
  }
  Eigen::FullPivLU<Eigen::MatrixXd> lu(S_FF);
  lu.setThreshold(1e-10);
  if (!lu.isInvertible()) return false;
  const Eigen::VectorXd x_F = lu.solve(rhs_F);
  for (Eigen::Index a = 0; a < k; ++a) x[set[static_cast<std::size_t>(a)]] = x_F[a];
  return true;
}

double dual_quadratic(double q, const Eigen::VectorXd& r, const Eigen::MatrixXd& S, const Eigen::VectorXd& nu) {
  return std::max(0.0, q - 2.0 * r.dot(nu) + nu.dot(S * nu));  // Q(nu) = ||g - B nu||^2 in H^-1
}

}  // namespace

Eigen::VectorXd nonnegative_projection_weights(const Eigen::Ref<const Eigen::MatrixXd>& S,
                                               const Eigen::Ref<const Eigen::VectorXd>& v) {
  check_sizes("nonnegative_projection_weights", S, v);
  const Eigen::Index m = v.size();
  const Eigen::MatrixXd S_sym = 0.5 * (S + S.transpose());
  const Eigen::VectorXd rhs = v;
  Eigen::VectorXd best = Eigen::VectorXd::Zero(m);  // F = {} : objective 0
  double best_objective = 0.0;
  Eigen::VectorXd mu;
  for (unsigned mask = 1; mask < (1u << m); ++mask) {
    if (!solve_on_set(S_sym, members(mask, m), rhs, mu)) continue;
    if ((mu.array() < 0.0).any()) continue;  // not a point of mu >= 0 with support F
    const double objective = 0.5 * mu.dot(S_sym * mu) - v.dot(mu);  // 1/2 mu^T S mu - v^T mu
    if (objective < best_objective) {
      best_objective = objective;
      best = mu;
    }
  }
  return best;
}

CpoDualSolution solve_cpo_dual(double q, const Eigen::Ref<const Eigen::VectorXd>& r,
                               const Eigen::Ref<const Eigen::MatrixXd>& S, const Eigen::Ref<const Eigen::VectorXd>& c,
                               double delta) {
  check_sizes("solve_cpo_dual", S, c);
  if (r.size() != c.size()) {
    throw std::invalid_argument("solve_cpo_dual: r has " + std::to_string(r.size()) + " entries, c " +
                                std::to_string(c.size()));
  }
  if (!std::isfinite(q) || !r.allFinite() || !(delta > 0.0) || !std::isfinite(delta)) {
    throw std::invalid_argument("solve_cpo_dual: q and r must be finite and delta > 0 (q=" + std::to_string(q) +
                                " delta=" + std::to_string(delta) + ")");
  }
  const Eigen::Index m = c.size();
  const Eigen::MatrixXd S_sym = 0.5 * (S + S.transpose());
  const Eigen::VectorXd r_vec = r;
  const Eigen::VectorXd c_vec = c;
  CpoDualSolution solution;

  // Feasibility: the H-smallest x with c + B^T x <= 0 is -H^-1 B mu0 with
  // 1/2 x^T H x = 1/2 mu0^T S mu0 (problem 2 with y = 0).
  const Eigen::VectorXd mu0 = nonnegative_projection_weights(S_sym, c_vec);
  const double smallest_kl = 0.5 * mu0.dot(S_sym * mu0);
  if (smallest_kl > delta) {
    solution.optim_case = MultiCpoCase::infeasible_recovery;
    solution.lambda = 0.0;
    solution.nu = mu0;
    solution.reward_weight = 0.0;
    solution.direction_scale = std::sqrt(delta / smallest_kl);  // 1/2 (s x0)^T H (s x0) = delta
    return solution;
  }

  // Every active set F: nu_F = S_FF^-1 (r_F + lambda c_F), lambda = sqrt(A_F / (2 delta - C_F)).
  double best_value = std::numeric_limits<double>::infinity();
  Eigen::VectorXd u, w, nu;
  for (unsigned mask = 0; mask < (1u << m); ++mask) {
    const std::vector<Eigen::Index> set = members(mask, m);
    // Unclamped solves: A_F and C_F need the exact S_FF^-1 r_F and S_FF^-1 c_F.
    Eigen::VectorXd r_F = Eigen::VectorXd::Zero(m), c_F = Eigen::VectorXd::Zero(m);
    for (Eigen::Index i : set) {
      r_F[i] = r_vec[i];
      c_F[i] = c_vec[i];
    }
    if (!solve_on_set(S_sym, set, r_F, u) || !solve_on_set(S_sym, set, c_F, w)) continue;
    const double A = std::max(0.0, q - r_F.dot(u));  // A_F = q - r_F^T S_FF^-1 r_F (>= 0 up to rounding)
    const double denominator = 2.0 * delta - c_F.dot(w);  // 2 delta - C_F
    if (!(denominator > 0.0)) continue;
    const double lambda = std::sqrt(A / denominator);
    nu = u + lambda * w;
    bool feasible = true;
    for (Eigen::Index i : set) feasible = feasible && nu[i] >= -1e-12 * (1.0 + std::abs(u[i]) + lambda * std::abs(w[i]));
    if (!feasible) continue;
    nu = nu.cwiseMax(0.0);
    // The dual objective at this nu, with lambda optimal for it: sqrt(2 delta Q(nu)) - c^T nu.
    const double value = std::sqrt(2.0 * delta * dual_quadratic(q, r_vec, S_sym, nu)) - c_vec.dot(nu);
    if (value < best_value) {
      best_value = value;
      solution.nu = nu;
    }
  }
  if (!std::isfinite(best_value)) {
    throw std::runtime_error("solve_cpo_dual: no active set gives a finite dual solution (q=" + std::to_string(q) +
                             ", delta=" + std::to_string(delta) + ")");
  }
  solution.lambda = std::sqrt(dual_quadratic(q, r_vec, S_sym, solution.nu) / (2.0 * delta));
  solution.direction_scale = 1.0 / (solution.lambda + 1e-8);  // CPO's epsilon, docs/algorithms.md#cpo step 7
  solution.reward_weight = 1.0;
  if ((c_vec.array() >= 0.0).any()) {
    solution.optim_case = MultiCpoCase::feasible_recovery;
  } else {
    solution.optim_case =
        (solution.nu.array() > 0.0).any() ? MultiCpoCase::constraint_cuts_region : MultiCpoCase::region_feasible;
  }
  return solution;
}

}  // namespace bsg::algos
