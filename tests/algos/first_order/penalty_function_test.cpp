// The penalty-function updates of the first-order family (OmniSafe's penalty_function/):
// P3O's minibatch loss (PPO's clipped reward loss plus kappa ReLU(L_C + J_C - d), with and
// without the clipped cost surrogate, a constraint on and one off) and its gradient against a
// hand-written loss and central differences; IPO's penalty kappa / (d - J_C) and its clamp by hand;
// one whole update of each (one pass, one minibatch) against Adam's first step on the
// finite-difference gradient of the hand-written loss; their keys, defaults and refusals.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "../../common/shipped_request.h"
#include "../../test_support.h"
#include "../algorithm_test_support.h"
#include "algos/first_order/ipo.h"
#include "algos/first_order/p3o.h"
#include "algos/first_order/ppo.h"
#include "common/run_config_resolve.h"

namespace bsg::algos {
namespace {
namespace penalty_function_test {

using testing::SyntheticBatch;
using testing::central_difference_gradient;

// -1/n sum_i min(rho_i A_i, clip(rho_i) A_i) over `rows`.
double hand_reward_loss(const Eigen::VectorXd& rho, const Eigen::VectorXd& a, double eps,
                        const std::vector<Eigen::Index>& rows) {
  double sum = 0;
  for (Eigen::Index i : rows) sum += -std::min(rho[i] * a[i], std::clamp(rho[i], 1 - eps, 1 + eps) * a[i]);
  return sum / static_cast<double>(rows.size());
}

// L_C = 1/n sum_i max(rho_i A^C_i, clip(rho_i) A^C_i) (clipped) or 1/n sum_i rho_i A^C_i over `rows`.
double hand_cost_surrogate(const Eigen::VectorXd& rho, const Eigen::VectorXd& ac, double eps, bool clipped,
                           const std::vector<Eigen::Index>& rows) {
  double sum = 0;
  for (Eigen::Index i : rows) {
    sum += clipped ? std::max(rho[i] * ac[i], std::clamp(rho[i], 1 - eps, 1 + eps) * ac[i]) : rho[i] * ac[i];
  }
  return sum / static_cast<double>(rows.size());
}

// P3O's minibatch loss: the reward loss plus kappa sum_j ReLU(L_Cj + v_j).
double hand_p3o_loss(const SyntheticBatch& batch, const Eigen::MatrixXd& cost_advantages,
                     const std::vector<double>& violations, double kappa, double eps, bool clipped,
                     const std::vector<Eigen::Index>& rows) {
  const Eigen::VectorXd rho = batch.ratios();
  double loss = hand_reward_loss(rho, batch.advantages, eps, rows);
  for (std::size_t j = 0; j < violations.size(); ++j) {
    const Eigen::VectorXd column = cost_advantages.col(static_cast<Eigen::Index>(j));
    loss += kappa * std::max(0.0, hand_cost_surrogate(rho, column, eps, clipped, rows) + violations[j]);
  }
  return loss;
}

// Moves the policy off the one that drew the batch so that ratios leave the clip range.
void move_policy(SyntheticBatch& batch, double scale, std::uint64_t seed) {
  Rng rng(seed);
  const auto p = static_cast<int>(batch.policy.mean_net().num_parameters());
  batch.policy.mean_net().set_parameters(batch.policy.mean_net().parameters() + scale * testing::random_vector(p, rng));
}

// Two cost columns: the batch's, and another whose surrogate has the other sign's share of samples.
Eigen::MatrixXd two_cost_columns(const SyntheticBatch& batch) {
  Eigen::MatrixXd costs(batch.advantages.size(), 2);
  costs.col(0) = batch.cost_advantages;
  costs.col(1) = batch.advantages.reverse() - 0.5 * batch.cost_advantages;
  return costs;
}

TEST(P3oLoss, MatchesTheHandWrittenLossAndFiniteDifferencesWithOneReluOnAndOneOff) {
  for (const bool clipped : {true, false}) {
    SCOPED_TRACE(clipped ? "clipped cost surrogate" : "unclipped cost surrogate");
    SyntheticBatch batch(40, 3, 4);
    const Eigen::MatrixXd anchor = batch.means();
    move_policy(batch, 0.05, 9);
    const double eps = 0.05, kappa = 3.0;
    const Eigen::VectorXd rho = batch.ratios();
    int held = 0;
    for (Eigen::Index i = 0; i < rho.size(); ++i) {
      // No ratio on a kink of min/max or clip, where the difference quotient would straddle it.
      ASSERT_GT(std::min(std::abs(rho[i] - (1 - eps)), std::abs(rho[i] - (1 + eps))), 1e-4) << i;
      held += rho[i] > 1 + eps || rho[i] < 1 - eps;
    }
    ASSERT_GT(held, 5);  // the clip acts on some samples
    const Eigen::MatrixXd costs = two_cost_columns(batch);
    PolicySurrogate surrogate(batch.observations, batch.actions, batch.old_log_probs, batch.advantages, costs);
    const std::vector<Eigen::Index> rows = {3, 17, 5, 39, 22, 0, 11, 30, 8, 26, 14};
    // Constraint 1 over its limit (its ReLU on), constraint 2 far under (off).
    const std::vector<double> violations = {4.0, -7.0};
    for (std::size_t j = 0; j < 2; ++j) {  // the ReLUs' arguments are far from their kink
      const Eigen::VectorXd column = costs.col(static_cast<Eigen::Index>(j));
      ASSERT_GT(std::abs(hand_cost_surrogate(rho, column, eps, clipped, rows) + violations[j]), 1.0);
    }
    P3oPenalty penalty(surrogate, violations, kappa, eps, clipped);
    SampleLossBatch losses(surrogate, anchor);
    const double penalty_value = penalty.evaluate(losses, batch.policy, rows, testing::single_process());
    EXPECT_TRUE(penalty.active(0));
    EXPECT_FALSE(penalty.active(1));
    Eigen::VectorXd gradient;
    const double sample_part = losses.loss(batch.policy, rows, penalty.sample_loss(batch.advantages), &gradient);
    // The per-sample loss leaves out the constant kappa (J_C - d) of an active ReLU; the penalty carries it.
    const double expected = hand_p3o_loss(batch, costs, violations, kappa, eps, clipped, rows);
    EXPECT_NEAR(sample_part + kappa * violations[0], expected, 1e-12);
    EXPECT_NEAR(hand_reward_loss(rho, batch.advantages, eps, rows) + penalty_value, expected, 1e-12);
    const Eigen::VectorXd fd = central_difference_gradient(
        batch, [&] { return hand_p3o_loss(batch, costs, violations, kappa, eps, clipped, rows); });
    EXPECT_LT((gradient - fd).norm(), 1e-6 * fd.norm()) << gradient.transpose() << "\n" << fd.transpose();
    // The cost term moves the gradient: without it, PPO's gradient differs.
    Eigen::VectorXd reward_only;
    losses.loss(batch.policy, rows, clipped_surrogate_loss(batch.advantages, eps), &reward_only);
    EXPECT_GT((gradient - reward_only).norm(), 0.1 * fd.norm());
  }
}

TEST(P3oLoss, BothRelusOffLeaveExactlyPposLossAndGradient) {
  SyntheticBatch batch(40, 5, 6);
  const Eigen::MatrixXd anchor = batch.means();
  move_policy(batch, 0.05, 10);
  const Eigen::MatrixXd costs = two_cost_columns(batch);
  PolicySurrogate surrogate(batch.observations, batch.actions, batch.old_log_probs, batch.advantages, costs);
  const std::vector<Eigen::Index> rows = testing::all_rows(40);
  P3oPenalty penalty(surrogate, {-30.0, -30.0}, 20.0, 0.2, true);
  SampleLossBatch losses(surrogate, anchor);
  EXPECT_EQ(penalty.evaluate(losses, batch.policy, rows, testing::single_process()), 0.0);
  Eigen::VectorXd p3o_gradient, ppo_gradient;
  const double p3o_loss = losses.loss(batch.policy, rows, penalty.sample_loss(batch.advantages), &p3o_gradient);
  const double ppo_loss = losses.loss(batch.policy, rows, clipped_surrogate_loss(batch.advantages, 0.2), &ppo_gradient);
  EXPECT_EQ(p3o_loss, ppo_loss);
  EXPECT_EQ(p3o_gradient, ppo_gradient);
}

// Adam's first step from zero moments, -lr g / (|g| + 1e-8) per parameter, for the
// finite-difference gradient g of the hand-written loss: the whole update of one pass over one
// minibatch, without gradient rescaling.
void expect_first_adam_step_on(const Eigen::VectorXd& theta_old, const Eigen::VectorXd& theta_new,
                               const Eigen::VectorXd& fd_gradient, double lr) {
  int checked = 0;
  for (Eigen::Index k = 0; k < theta_old.size(); ++k) {
    if (std::abs(fd_gradient[k]) < 1e-4) continue;  // there the difference quotient's error could flip the sign
    EXPECT_NEAR(theta_new[k] - theta_old[k], -lr * fd_gradient[k] / (std::abs(fd_gradient[k]) + 1e-8), 1e-9 * lr) << k;
    ++checked;
  }
  EXPECT_GT(checked, theta_old.size() / 2);
}

RunConfig one_step_config(Algorithm alg) {
  RunConfig config = testing::config_for(alg);
  config.first_order.update_iters = 1;
  config.first_order.policy_minibatch_size = 1000;  // one minibatch: the whole batch
  config.first_order.max_grad_norm = 0.0;
  config.first_order.actor_lr = 1e-3;
  return config;
}

// One update of a fresh `Update` on the batch with one constraint at J_C = cost.
template <class Update>
PolicyUpdateResult one_update(SyntheticBatch& batch, const RunConfig& config, double cost) {
  PolicySurrogate surrogate = batch.surrogate();
  Rng shuffle(1);
  PolicyUpdateInputs inputs = testing::inputs_for(batch, surrogate, cost, 100.0);
  inputs.minibatch_rng = &shuffle;
  Update update(config);
  return update.update(inputs);
}

TEST(P3o, OneStepIsAdamsFirstStepOnTheHandWrittenLossAndLogsThePenalty) {
  for (const double cost : {31.0, 12.0}) {  // d = 25: the ReLU on, then off
    SCOPED_TRACE(cost);
    SyntheticBatch batch(64, 3, 4);
    const RunConfig config = one_step_config(Algorithm::p3o);
    const Eigen::VectorXd theta_old = batch.policy.mean_net().parameters();
    const std::vector<Eigen::Index> rows = testing::all_rows(64);
    const std::vector<double> violation = {cost - config.cost_limit};
    const Eigen::MatrixXd costs = batch.cost_advantages;
    const auto hand_loss = [&] {
      return hand_p3o_loss(batch, costs, violation, config.first_order.p3o_kappa, config.first_order.clip, true, rows);
    };
    const Eigen::VectorXd fd = central_difference_gradient(batch, hand_loss);
    // At theta_old every rho is 1: L_C = mean A^C, the penalty kappa max(0, mean A^C + J_C - d).
    const double penalty = config.first_order.p3o_kappa * std::max(0.0, batch.cost_advantages.mean() + violation[0]);
    ASSERT_EQ(penalty > 0.0, cost > config.cost_limit);
    const PolicyUpdateResult result = one_update<P3o>(batch, config, cost);
    EXPECT_NEAR(result.value("p3o_penalty"), penalty, 1e-12);
    EXPECT_NEAR(result.value("Loss/Pi"), -batch.advantages.mean(), 1e-12);  // l_R at theta_old
    EXPECT_EQ(result.value("Misc/StopIter"), 1.0);
    expect_first_adam_step_on(theta_old, batch.policy.mean_net().parameters(), fd, config.first_order.actor_lr);
  }
}

TEST(IpoPenalties, AreKappaOverTheSlackClampedAtTheMaximum) {
  // p = kappa / (d - J_C + 1e-8), the 1e-8 OmniSafe's guard against a zero slack.
  const std::vector<ConstraintEstimate> constraints = {
      {15.0, 25.0},     // 0.01 / 10 = 0.001
      {24.995, 25.0},   // 0.01 / 0.005 = 2 > p_max: 1
      {30.0, 25.0},     // past the pole (negative): p_max
      {25.0, 25.0},     // at the pole: 0.01 / 1e-8 > p_max
      {1.0, 5.0}};      // 0.01 / 4 = 0.0025
  const std::vector<double> p = ipo_penalties(constraints, 0.01, 1.0);
  ASSERT_EQ(p.size(), 5u);
  EXPECT_NEAR(p[0], 0.01 / (10 + 1e-8), 1e-15);
  EXPECT_EQ(p[1], 1.0);
  EXPECT_EQ(p[2], 1.0);
  EXPECT_EQ(p[3], 1.0);
  EXPECT_NEAR(p[4], 0.01 / (4 + 1e-8), 1e-15);
  EXPECT_NEAR(ipo_penalties(std::vector<ConstraintEstimate>{{20.0, 25.0}}, 2.0, 0.5)[0], 2.0 / (5 + 1e-8), 1e-15);
  EXPECT_EQ(ipo_penalties(std::vector<ConstraintEstimate>{{22.0, 25.0}}, 2.0, 0.5)[0], 0.5);  // 2 / 3 > 0.5
}

TEST(Ipo, OneStepIsAdamsFirstStepOnTheClippedLossOfTheHandPenalisedAdvantage) {
  for (const double cost : {20.0, 40.0}) {  // d = 25: p = 0.01 / 5 = 0.002, then p_max = 1
    SCOPED_TRACE(cost);
    SyntheticBatch batch(64, 5, 6);
    const RunConfig config = one_step_config(Algorithm::ipo);
    const double p = cost < config.cost_limit ? 0.01 / (config.cost_limit - cost + 1e-8) : 1.0;
    const Eigen::VectorXd a_hat = (batch.advantages - p * batch.cost_advantages) / (1.0 + p);
    const Eigen::VectorXd theta_old = batch.policy.mean_net().parameters();
    const std::vector<Eigen::Index> rows = testing::all_rows(64);
    const Eigen::VectorXd fd = central_difference_gradient(
        batch, [&] { return hand_reward_loss(batch.ratios(), a_hat, config.first_order.clip, rows); });
    const PolicyUpdateResult result = one_update<Ipo>(batch, config, cost);
    EXPECT_NEAR(result.value("ipo_penalty"), p, 1e-15);
    EXPECT_NEAR(result.value("Loss/Pi"), -a_hat.mean(), 1e-12);  // the loss of A_hat at theta_old (rho = 1)
    expect_first_adam_step_on(theta_old, batch.policy.mean_net().parameters(), fd, config.first_order.actor_lr);
  }
}

TEST(Ipo, EachConstraintHasItsOwnPenaltyAndColumn) {
  SyntheticBatch batch(64, 7, 8);
  RunConfig config = one_step_config(Algorithm::ipo);
  config.constraints = {{{"cost_outside_bounds"}, 25.0}, {{"cost_velocity_violation"}, 5.0}};
  const Eigen::MatrixXd costs = two_cost_columns(batch);
  PolicySurrogate surrogate(batch.observations, batch.actions, batch.old_log_probs, batch.advantages, costs);
  const std::vector<ConstraintEstimate> constraints = {{20.0, 25.0}, {9.0, 5.0}};  // p = 0.002, p_max = 1
  Rng shuffle(1);
  PolicyUpdateInputs inputs = testing::inputs_for(batch, surrogate, 20.0, 100.0);
  inputs.constraints = constraints;
  inputs.minibatch_rng = &shuffle;
  Ipo ipo(config);
  const std::vector<std::string> names = ipo.diagnostic_names();
  ASSERT_GE(names.size(), 2u);
  EXPECT_EQ(names[names.size() - 2], "constraint_1_ipo_penalty");
  EXPECT_EQ(names.back(), "constraint_2_ipo_penalty");
  const PolicyUpdateResult result = ipo.update(inputs);
  const double p1 = 0.01 / (5 + 1e-8);
  EXPECT_NEAR(result.value("constraint_1_ipo_penalty"), p1, 1e-15);
  EXPECT_EQ(result.value("constraint_2_ipo_penalty"), 1.0);
  // Loss/Pi at theta_old: -mean((A - p1 A^C1 - A^C2) / (2 + p1)).
  const Eigen::VectorXd a_hat = (batch.advantages - p1 * costs.col(0) - costs.col(1)) / (2.0 + p1);
  EXPECT_NEAR(result.value("Loss/Pi"), -a_hat.mean(), 1e-12);
}

TEST(PenaltyFunctionConfig, ShippedDefaultsAreOmniSafes) {
  const RunConfig p3o = resolve_run_config(testing::shipped_request("SafetyBallCircle-v0", "p3o", {})).config;
  EXPECT_EQ(p3o.first_order.p3o_kappa, 20.0);
  EXPECT_TRUE(p3o.first_order.p3o_cost_clip);
  EXPECT_EQ(p3o.first_order.update_iters, 10);
  EXPECT_EQ(p3o.first_order.clip, 0.2);
  EXPECT_TRUE(p3o.use_cost_value_function);
  const RunConfig ipo = resolve_run_config(testing::shipped_request("SafetyBallCircle-v0", "ipo", {})).config;
  EXPECT_EQ(ipo.first_order.ipo_kappa, 0.01);
  EXPECT_EQ(ipo.first_order.ipo_penalty_max, 1.0);
  EXPECT_EQ(ipo.first_order.update_iters, 10);
  EXPECT_TRUE(ipo.use_cost_value_function);
  // Several constraints are accepted: P3O and IPO have a penalty per constraint.
  const std::string two = "constraints=[{terms: [cost_outside_bounds], limit: 20}, {terms: [cost_velocity_violation], limit: 5}]";
  EXPECT_EQ(resolve_run_config(testing::shipped_request("SafetyBallRun-v0", "p3o", {two})).config.constraints.size(), 2u);
  EXPECT_EQ(resolve_run_config(testing::shipped_request("SafetyBallRun-v0", "ipo", {two})).config.constraints.size(), 2u);
}

TEST(PenaltyFunctionConfig, BadKeysAreRefusedInOneLineNamingTheKey) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"p3o", "p3o_kappa=0"},       {"p3o", "p3o_kappa=-1"},          {"p3o", "p3o_cost_clip=maybe"},
      {"ipo", "ipo_kappa=0"},       {"ipo", "ipo_penalty_max=0"},     {"ipo", "ipo_kappa=nan"},
      {"ppo-lag", "p3o_kappa=1"},   {"p3o", "ipo_kappa=1"},           {"ipo", "p3o_cost_clip=false"},
      {"p3o", "lambda_lr=0.1"},     {"ipo", "lagrangian_multiplier_init=1"}, {"p3o", "cg_iters=5"},
      {"trpo", "ipo_penalty_max=2"}, {"ipo", "focops_lam=2"}};
  for (const auto& [alg, setting] : cases) {
    SCOPED_TRACE(alg + " " + setting);
    const std::string m = testing::config_error_of(testing::shipped_request("SafetyBallCircle-v0", alg, {setting}));
    const std::string key = setting.substr(0, setting.find('='));
    EXPECT_TRUE(testing::contains(m, "'" + key + "'")) << m;
    EXPECT_EQ(m.find('\n'), std::string::npos) << m;
  }
  RunConfig direct = testing::config_for(Algorithm::p3o);
  direct.first_order.p3o_kappa = 0.0;
  EXPECT_THROW(P3o{direct}, std::invalid_argument);
  direct = testing::config_for(Algorithm::ipo);
  direct.first_order.ipo_penalty_max = -1.0;
  EXPECT_THROW(Ipo{direct}, std::invalid_argument);
}

}  // namespace penalty_function_test
}  // namespace
}  // namespace bsg::algos
