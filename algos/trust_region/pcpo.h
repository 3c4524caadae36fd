// PCPO, projection-based constrained policy optimisation (docs/algorithms.md#pcpo; Yang et
// al., ICLR 2020; not in the original repository):
//   1. l_R(theta_old), g = avg grad L_R, x = CG(F, g), q = x^T F x,
//      eta = sqrt(2 delta / (q + 1e-8)), reward step Delta_R = eta x
//   2. L_C(theta_old), b = avg grad L_C, c = (J_C - d) / (L + 1e-8)
//   3. linearised violation after the reward step v = c + b^T Delta_R
//   4. projection onto {Delta : c + b^T Delta <= 0} in the metric L:
//        KL (L = F): p = CG(F, b), s = b^T p,  nu = max(0, v) / (s + 1e-8),   Delta = Delta_R - nu p
//        L2 (L = I):               s = b^T b,  nu = max(0, v) / (s + 1e-8),   Delta = Delta_R - nu b
//      with nu = 0 if b^T b <= 1e-6 (a design decision, not in the paper)
//   5. line search B (budget 25): reward test only if c < 0; pcpo_line_search:
//      false applies Delta directly (the authors' release)
// Logs: the CPO set with eta as Misc/Alpha, nu as Misc/Nu_star, r = b^T x
// (so that v = c + eta r), s as above, A = B = Lambda_star = 0 (not defined),
// OptimCase 1 if c >= 0 else 2.
//
// Parameters (RunConfig): target_kl 1e-4, cg_iters 10, cg_damping 0.1,
// backtrack_budget 25, backtrack_decay 0.8, kl_accept_factor 1.5, cost_limit 25,
// pcpo_projection kl, pcpo_line_search true.
//
// With m >= 2 constraints (docs/algorithms.md#several-constraints) step 4 projects Delta_R onto
// the intersection of the m half-spaces {Delta : c_j + b_j^T Delta <= 0} in the
// metric L, a small QP solved exactly (constraint_qp.h): Delta = Delta_R - sum_j mu_j L^-1 b_j
// with mu >= 0 minimising 1/2 mu^T S mu - v^T mu, S_jk = b_j^T L^-1 b_k,
// v_j = c_j + b_j^T Delta_R; constraints with b_j^T b_j <= 1e-6 are left out
// (mu_j = 0) as the single constraint's guard does. The line search checks
// every constraint; its reward test only if every c_j < 0.
#pragma once

#include <Eigen/Core>

#include "algos/core/algorithm.h"
#include "algos/trust_region/trust_region_steps.h"
#include "algos/trust_region/conjugate_gradient.h"
#include "common/run_config.h"

namespace bsg::algos {

struct PcpoStepOptions {
  double target_kl = 1e-4;  // delta
  PcpoProjection projection = PcpoProjection::kl;
  ConjugateGradientOptions conjugate_gradient;
};

struct PcpoStep {
  Eigen::VectorXd reward_direction;   // x = CG(F, g)
  double q = 0.0;                     // x^T F x
  double eta = 0.0;                   // sqrt(2 delta / (q + 1e-8))
  Eigen::VectorXd reward_step;        // Delta_R = eta x
  double r = 0.0;                     // b^T x
  double violation_after_reward_step = 0.0;  // v = c + b^T Delta_R
  Eigen::VectorXd projection_direction;      // p = CG(F, b) (KL) or b (L2)
  double s = 0.0;                     // b^T p (KL) or b^T b (L2)
  double nu = 0.0;                    // max(0, v) / (s + 1e-8)
  Eigen::VectorXd full_step;          // Delta = Delta_R - nu p
};

// Steps 1, 3 and 4 for a given Fisher operator, g, b and c.
PcpoStep pcpo_step(const LinearOperator& fisher, const Eigen::Ref<const Eigen::VectorXd>& reward_gradient,
                   const Eigen::Ref<const Eigen::VectorXd>& cost_gradient, double constraint_violation,
                   const PcpoStepOptions& options);

class Pcpo final : public OnPolicyAlgorithm {
 public:
  explicit Pcpo(const RunConfig& config);

  std::string_view name() const override { return "pcpo"; }
  PolicyUpdateResult update(const PolicyUpdateInputs& inputs) override;
  std::vector<std::string> diagnostic_names() const override;

 private:
  PolicyUpdateResult update_several(const PolicyUpdateInputs& inputs, const std::vector<ConstraintEstimate>& constraints);
};

}  // namespace bsg::algos
