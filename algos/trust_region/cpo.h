// CPO, constrained policy optimisation (docs/algorithms.md#cpo; Achiam et al. 2017, as the
// original's algs/cpo/cpo.py, whose dual follows safety-starter-agents):
//   1. l_R(theta_old), g = avg grad L_R
//   2. x = CG(F, g), q = x^T F x, alpha_T = sqrt(2 delta / (q + 1e-8))
//   3. L_C(theta_old), b = avg grad L_C
//   4. c = (J_C - d) / (L + 1e-8)       (per-step violation, same scale as L_C)
//   5. p = CG(F, b), r = g^T p, s = b^T p
//   6. case: 4 if b^T b <= 1e-6 and c < 0; else A = q - r^2/s, B = 2 delta - c^2/s and
//      3 (c<0, B<0), 2 (c<0, B>=0), 1 (c>=0, B>=0), 0 (c>=0, B<0)
//   7. the step of the case (cpo_step below)
//   8. line search B (budget 20, Q11); the reward test only in cases 2, 3, 4
// Q10: cpo_r_sign original replicates the original's sign of r in the dual of
// cases 1 and 2 (nu* = (lambda c - r)_+ / s with r = g^T p); corrected uses
// r := -g^T p there (the true optimum of the linear-quadratic sub-problem).
// The logged Misc/r is g^T p either way. A < 0 (rounding; sqrt(A/B) = NaN) is
// an error unless cpo_clamp_a clamps it at 0; B = 0 is always an error.
//
// Parameters (RunConfig): target_kl 1e-4, cg_iters 10, cg_damping 0.1,
// backtrack_budget 20, backtrack_decay 0.8, kl_accept_factor 1.5, cost_limit 25,
// cpo_r_sign original, cpo_clamp_a false.
//
// With m >= 2 constraints (docs/algorithms.md#several-constraints) the update solves the
// trust-region problem with every constraint through its dual in m + 1
// variables (constraint_qp.h, the true dual: cpo_r_sign does not apply), with
// c_j = (J_Cj - d_j) / (L + 1e-8), b_j = avg grad L_Cj and p_j = CG(F, b_j);
// the line search accepts a trial only if every L_Cj passes the test of
// docs/algorithms.md#constrained-line-search. With one constraint the update is the one above.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "algos/core/algorithm.h"
#include "algos/trust_region/trust_region_steps.h"
#include "algos/trust_region/conjugate_gradient.h"
#include "algos/trust_region/natural_gradient.h"
#include "common/run_config.h"

namespace bsg::algos {

// The case numbers of docs/algorithms.md#cpo (logged as Misc/OptimCase).
enum class CpoCase : int {
  infeasible_recovery = 0,       // c >= 0, B < 0: pure cost decrease
  feasible_recovery = 1,         // c >= 0, B >= 0
  constraint_cuts_region = 2,    // c < 0, B >= 0
  region_feasible = 3,           // c < 0, B < 0: TRPO step
  negligible_cost_gradient = 4,  // b^T b <= 1e-6, c < 0: TRPO step
};

// Cases 2-4 start from a feasible policy (c < 0): there the line search also
// asks the reward surrogate to improve (docs/algorithms.md#cpo, step 8).
constexpr bool starts_feasible(CpoCase optim_case) {
  return optim_case == CpoCase::constraint_cuts_region || optim_case == CpoCase::region_feasible ||
         optim_case == CpoCase::negligible_cost_gradient;
}

struct CpoStepOptions {
  double target_kl = 1e-4;                 // delta
  CpoRSign r_sign = CpoRSign::original;    // Q10
  bool clamp_a = false;                    // clamp A < 0 at 0 instead of throwing
  ConjugateGradientOptions conjugate_gradient;
};

struct CpoStep {
  Eigen::VectorXd reward_direction;  // x = CG(F, g)
  Eigen::VectorXd cost_direction;    // p = CG(F, b)
  double q = 0.0;                    // x^T F x
  double trpo_step_size = 0.0;       // alpha_T = sqrt(2 delta / (q + 1e-8))
  double r = 0.0;                    // g^T p (as logged; the dual uses -r if corrected)
  double s = 0.0;                    // b^T p
  double A = 0.0;                    // q - r^2 / s (0 in case 4)
  double B = 0.0;                    // 2 delta - c^2 / s (0 in case 4)
  CpoCase optim_case = CpoCase::region_feasible;
  double lambda_star = 0.0;          // lambda*
  double nu_star = 0.0;              // nu*
  Eigen::VectorXd full_step;         // Delta
};

// Steps 2 and 5-7 for a given Fisher operator, g, b and c. Throws
// std::runtime_error on degenerate numerics (A < 0 without clamp_a, A/B not
// finite, non-finite step).
CpoStep cpo_step(const LinearOperator& fisher, const Eigen::Ref<const Eigen::VectorXd>& reward_gradient,
                 const Eigen::Ref<const Eigen::VectorXd>& cost_gradient, double constraint_violation,
                 const CpoStepOptions& options);

// P = [CG(F, b_1) .. CG(F, b_m)], one column per constraint gradient.
Eigen::MatrixXd conjugate_gradient_columns(const LinearOperator& fisher, const Eigen::Ref<const Eigen::MatrixXd>& costs,
                                           const ConjugateGradientOptions& options);

// The per-constraint diagnostics of CPO and PCPO with m >= 2: constraint_<j>_nu, j = 1..m.
std::vector<std::string> constraint_multiplier_names(int constraint_count);

// The first steps CPO and PCPO share with m >= 2 constraints: c_j, theta_old
// with the surrogates there, g and B, and x = CG(F, g) with q and the TRPO step.
struct SeveralConstraintsStart {
  // F at theta_old; owned here (on the heap, so `fisher` stays valid when the struct moves).
  std::unique_ptr<FisherVectorProduct> fisher_product;
  LinearOperator fisher;
  Eigen::VectorXd violations;  // c_j = (J_Cj - d_j) / (L + 1e-8)
  PolicyUpdateStart start;
  ConstraintGradients gradients;
  NaturalGradientStep natural;
};
SeveralConstraintsStart begin_several_constraints_update(const PolicyUpdateInputs& inputs,
                                                         const std::vector<ConstraintEstimate>& constraints,
                                                         const RunConfig& config);

// Their diagnostics: the common and TRPO columns, cost_gradient_norm = |B|_F, cpo_q,
// the algorithm's `extra` columns, then constraint_<j>_nu = nu[j].
std::vector<NamedScalar> several_constraints_diagnostics(const PolicyUpdateInputs& inputs,
                                                         const SeveralConstraintsStart& begun,
                                                         const LineSearchResult& search,
                                                         const std::vector<NamedScalar>& extra,
                                                         const Eigen::VectorXd& nu);

// Steps 1-8 with one constraint for a given c: Cpo::update with c = (J_C - d) / (L + 1e-8), and
// MACPO's agent step (algos/multi_agent/macpo_agent_step.h) with the agent's corrected surrogate
// and its own c. On return the policy holds theta_old + the accepted step (theta_old bit for bit
// if none was accepted).
struct SingleConstraintCpoUpdate {
  PolicyUpdateStart start;    // theta_old, l_R(theta_old), L_C(theta_old)
  PolicyGradients gradients;  // g, b
  CpoStep step;
  LineSearchResult search;
};
SingleConstraintCpoUpdate single_constraint_cpo_update(const PolicyUpdateInputs& inputs, double constraint_violation,
                                                       const RunConfig& config);
// Its columns: the common, TRPO and CPO ones (Cpo::diagnostic_names() with one constraint).
std::vector<NamedScalar> single_constraint_cpo_diagnostics(const PolicyUpdateInputs& inputs,
                                                           const SingleConstraintCpoUpdate& update);

class Cpo final : public OnPolicyAlgorithm {
 public:
  explicit Cpo(const RunConfig& config);

  std::string_view name() const override { return "cpo"; }
  PolicyUpdateResult update(const PolicyUpdateInputs& inputs) override;
  std::vector<std::string> diagnostic_names() const override;

 private:
  PolicyUpdateResult update_several(const PolicyUpdateInputs& inputs, const std::vector<ConstraintEstimate>& constraints);
};

// The nine CPO columns after the TRPO set (also PCPO's, with A, B and lambda*
// 0: not defined there), in docs/algorithms.md#logged-columns order. One
// table, cpo_diagnostics, gives the names and the values.
struct CpoColumns {
  double cost_gradient_norm = 0.0;  // |b|
  double A = 0.0;
  double B = 0.0;
  double q = 0.0;
  double r = 0.0;
  double s = 0.0;
  double lambda_star = 0.0;
  double nu_star = 0.0;
  double optim_case = 0.0;
};
void append_cpo_diagnostics(std::vector<NamedScalar>& diagnostics, const CpoColumns& columns);
std::vector<std::string> cpo_diagnostic_names();

}  // namespace bsg::algos
