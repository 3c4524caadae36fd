// The building blocks the five trust-region updates (TRPO, TRPO-L, CPO, PDO,
// PCPO) share: CG, FVP and line-search options from the RunConfig, the Fisher
// operator, rank-averaged gradients, the line searches' evaluators and
// applying the accepted step (docs/algorithms.md#algorithm-updates).
#pragma once

#include <Eigen/Core>
#include <span>
#include <vector>

#include "algos/core/algorithm.h"
#include "algos/core/gaussian_policy.h"
#include "algos/core/policy_surrogate.h"
#include "algos/trust_region/conjugate_gradient.h"
#include "algos/trust_region/fisher_vector_product.h"
#include "algos/trust_region/line_search.h"
#include "common/mpi_context.h"
#include "common/run_config.h"

namespace bsg::algos {

// CG, FVP and line-search options from the RunConfig (cg_iters, cg_damping,
// fvp_subsample, backtrack_budget, backtrack_decay, target_kl, kl_accept_factor).
ConjugateGradientOptions conjugate_gradient_options(const RunConfig& config);
FisherVectorProductOptions fisher_vector_product_options(const RunConfig& config);
LineSearchOptions line_search_options(const RunConfig& config);

// The LinearOperator view of a FisherVectorProduct (which must outlive it).
LinearOperator as_linear_operator(FisherVectorProduct& fisher);

// g = avg grad L_R and b = avg grad L_C at the policy's parameters, with one
// allreduce of length 2P (docs/algorithms.md#surrogates-and-gradients).
struct PolicyGradients {
  Eigen::VectorXd reward;  // g
  Eigen::VectorXd cost;    // b
};
PolicyGradients averaged_policy_gradients(const PolicyUpdateInputs& inputs);

// g and B = [b_1 .. b_m] (P x m, b_j = avg grad L_Cj) with one allreduce of length (1 + m) P.
struct ConstraintGradients {
  Eigen::VectorXd reward;  // g
  Eigen::MatrixXd costs;   // B
};
ConstraintGradients averaged_constraint_gradients(const PolicyUpdateInputs& inputs);

// c_i = (J_Ci - d_i) / (L + 1e-8) for every constraint (per_step_constraint_violation).
Eigen::VectorXd per_step_constraint_violations(std::span<const ConstraintEstimate> constraints,
                                               double mean_episode_length);

// L_Cj of a surrogate evaluation averaged over ranks (m values, one allreduce).
Eigen::VectorXd averaged_cost_surrogates(const SurrogateValues& values, int constraint_count, const MpiContext& mpi);

// Line search B's callable for m constraints: l_R and KL as constrained_evaluator,
// and in place of L_C the largest margin max_j (L_Cj(theta) - L_Cj_old - allowance_j)
// after averaging L_Cj over ranks (collective), so that the search, given
// cost_surrogate_old = 0 and c = 0, accepts a trial only if every constraint's
// surrogate rose by at most its allowance max(-c_j, 0).
ConstrainedEvaluator all_constraints_evaluator(const PolicyUpdateInputs& inputs, const Eigen::VectorXd& theta_old,
                                               Eigen::VectorXd averaged_cost_surrogates_old,
                                               Eigen::VectorXd allowances);

// theta <- theta_old + step if the search accepted a trial, else theta <-
// theta_old exactly (bit-identical; no "+ 0" which could flip a -0.0).
void apply_line_search_result(GaussianPolicy& policy, const Eigen::VectorXd& theta_old,
                              const LineSearchResult& result);

// The per-step constraint violation c = (J_C - d) / (L + 1e-8) of CPO and
// PCPO (docs/algorithms.md#cpo, step 4); throws if J_C or L is not finite or L < 0.
double per_step_constraint_violation(double mean_episode_cost, double mean_episode_length, double cost_limit);

// Line search B over every constraint: with all_constraints_evaluator, L_Cj(theta_old)
// from start.before and the allowances max(-c_j, 0) of the violations c.
LineSearchResult constrained_line_search_all(const PolicyUpdateInputs& inputs, const PolicyUpdateStart& start,
                                             const Eigen::VectorXd& full_step, const Eigen::VectorXd& violations,
                                             bool require_reward_improvement, const RunConfig& config);

// Line search A's callable for the loss l = -(reward_weight L_R + cost_weight L_C)
// at theta_old + step (TRPO, PDO: weights (1, 0); TRPO-L: 1/(1+lambda), -lambda/(1+lambda)).
LossEvaluator surrogate_loss_evaluator(const PolicyUpdateInputs& inputs, const Eigen::VectorXd& theta_old,
                                       double reward_weight, double cost_weight);
// Line search B's callable: l_R, L_C and KL at theta_old + step.
ConstrainedEvaluator constrained_evaluator(const PolicyUpdateInputs& inputs, const Eigen::VectorXd& theta_old);

// Line search A's callable for the loss -(w_R L_R + sum_j w_j L_Cj) of
// core/algorithm.h's weighted_surrogate_loss (TRPO-L with m multipliers).
LossEvaluator surrogate_loss_evaluator(const PolicyUpdateInputs& inputs, const Eigen::VectorXd& theta_old,
                                       double reward_weight, std::vector<double> cost_weights);

}  // namespace bsg::algos
