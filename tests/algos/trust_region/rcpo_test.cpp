// RCPO's update (docs/algorithms.md#rcpo): the multiplier steps first (SGD by hand), then the
// step is the natural-gradient step, without a line search, on the advantage of the penalised
// reward r - lambda c: the oracle is TRPO's accepted full step on a batch whose reward advantage
// is the GAE of r - lambda c with the value V - lambda V_C, computed by hand over a path, over
// 1 + lambda; the line-search keys are refused for it; several constraints each have a multiplier.
#include "algos/trust_region/rcpo.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "../../common/shipped_request.h"
#include "../../test_support.h"
#include "../algorithm_test_support.h"
#include "algos/core/buffer.h"
#include "algos/trust_region/lag_trpo.h"
#include "algos/trust_region/trpo.h"

namespace bsg::algos {
namespace {

using testing::SyntheticBatch;

constexpr double kGamma = 0.9, kLam = 0.8;

// One path of the batch's length with random rewards, costs and values, through the buffer's GAE.
struct PenalisedPath {
  Eigen::VectorXd rewards, costs, values, cost_values;
  Eigen::VectorXd advantages, cost_advantages;  // the buffer's GAE

  explicit PenalisedPath(Eigen::Index n) : rewards(n), costs(n), values(n), cost_values(n) {
    Rng rng(77);
    Buffer buffer(n, 1, 1, BufferOptions{.gamma = kGamma, .lam = kLam, .lam_c = kLam});
    for (Eigen::Index t = 0; t < n; ++t) {
      rewards[t] = standard_normal(rng);
      costs[t] = uniform(rng, 0.0, 1.0) < 0.3 ? 1.0 : 0.0;
      values[t] = standard_normal(rng);
      cost_values[t] = uniform(rng, 0.0, 3.0);
      buffer.store(Eigen::VectorXd::Zero(1), Eigen::VectorXd::Zero(1), rewards[t], costs[t], values[t], cost_values[t],
                   0.0);
    }
    buffer.finish_path(0.0, 0.0, std::nullopt, PathEnd::episode_end);
    advantages = buffer.advantages();
    cost_advantages = buffer.cost_advantages();
  }

  // By hand: GAE of the penalised reward r - lambda c with the penalised value V - lambda V_C.
  Eigen::VectorXd penalised_advantages(double lambda) const {
    const Eigen::Index n = rewards.size();
    Eigen::VectorXd gae(n);
    double running = 0.0;
    for (Eigen::Index t = n - 1; t >= 0; --t) {
      const double value = values[t] - lambda * cost_values[t];
      const double next = t + 1 < n ? values[t + 1] - lambda * cost_values[t + 1] : 0.0;  // a true terminal
      const double delta = rewards[t] - lambda * costs[t] + kGamma * next - value;
      running = delta + kGamma * kLam * running;
      gae[t] = running;
    }
    return gae;
  }
};

RunConfig sgd_config() {
  RunConfig config = testing::config_for(Algorithm::rcpo);
  config.multiplier.lambda_optimizer = LambdaOptimizer::sgd;
  config.multiplier.lambda_lr = 0.05;
  return config;
}

TEST(Rcpo, StepsOnTheAdvantageOfThePenalisedRewardWithoutALineSearch) {
  const PenalisedPath path(64);
  // lambda = 0.001 + 0.05 (30 - 25) = 0.251 (SGD by hand).
  const double lambda = 0.251;
  SyntheticBatch batch(64, 3, 4);
  batch.advantages = path.advantages;
  batch.cost_advantages = path.cost_advantages;
  SyntheticBatch oracle_batch(64, 3, 4);
  oracle_batch.advantages = path.penalised_advantages(lambda) / (1.0 + lambda);
  // The oracle's check: the buffer's advantages and the hand-penalised GAE agree (GAE is linear).
  ASSERT_LT((path.advantages - lambda * path.cost_advantages - path.penalised_advantages(lambda)).cwiseAbs().maxCoeff(),
            1e-12);

  PolicySurrogate oracle_surrogate = oracle_batch.surrogate();
  Trpo trpo(testing::config_for(Algorithm::trpo));
  const PolicyUpdateResult oracle = trpo.update(testing::inputs_for(oracle_batch, oracle_surrogate, 0.0, 100.0));
  ASSERT_EQ(oracle.value("Misc/AcceptanceStep"), 1.0);  // TRPO took its full step: the same step without a search

  PolicySurrogate surrogate = batch.surrogate();
  Rcpo rcpo(sgd_config());
  const PolicyUpdateResult result = rcpo.update(testing::inputs_for(batch, surrogate, 30.0, 100.0));
  EXPECT_NEAR(result.value("LagrangeMultiplier"), lambda, 1e-15);
  EXPECT_EQ(result.value("Misc/AcceptanceStep"), 1.0);
  EXPECT_NEAR(result.value("Loss/Pi"), oracle.value("Loss/Pi"), 1e-12);
  const Eigen::VectorXd theta = batch.policy.mean_net().parameters();
  const Eigen::VectorXd expected = oracle_batch.policy.mean_net().parameters();
  EXPECT_LE((theta - expected).cwiseAbs().maxCoeff(), 1e-10 * expected.cwiseAbs().maxCoeff());
}

TEST(Rcpo, TakesTheFullStepWhereTrpoLsLineSearchBacktracks) {
  // TRPO-L accepting only a KL of half the trust region backtracks from the full step (whose KL is
  // about delta); RCPO, which has no line search, applies it.
  RunConfig lag_config = sgd_config();
  lag_config.alg = Algorithm::lag_trpo;
  lag_config.trust_region.kl_accept_factor = 0.5;
  const RunConfig rcpo_config = sgd_config();
  SyntheticBatch lag_batch(64, 3, 4);
  SyntheticBatch rcpo_batch(64, 3, 4);
  const Eigen::VectorXd theta_old = rcpo_batch.policy.mean_net().parameters();
  PolicySurrogate lag_surrogate = lag_batch.surrogate();
  PolicySurrogate rcpo_surrogate = rcpo_batch.surrogate();
  LagTrpo lag(lag_config);
  Rcpo rcpo(rcpo_config);
  const PolicyUpdateResult lag_result = lag.update(testing::inputs_for(lag_batch, lag_surrogate, 30.0, 100.0));
  const PolicyUpdateResult rcpo_result = rcpo.update(testing::inputs_for(rcpo_batch, rcpo_surrogate, 30.0, 100.0));
  ASSERT_GT(lag_result.value("Misc/AcceptanceStep"), 1.0);
  EXPECT_EQ(rcpo_result.value("Misc/AcceptanceStep"), 1.0);
  // Both computed the same direction and alpha; RCPO applied alpha x whole.
  EXPECT_EQ(rcpo_result.value("Misc/Alpha"), lag_result.value("Misc/Alpha"));
  EXPECT_NEAR((rcpo_batch.policy.mean_net().parameters() - theta_old).norm(),
              rcpo_result.value("Misc/Alpha") * rcpo_result.value("Misc/H_inv_g"), 1e-12);
}

TEST(Rcpo, EachConstraintHasItsOwnMultiplier) {
  SyntheticBatch batch(64, 5, 6);
  Eigen::MatrixXd cost_advantages(64, 2);
  cost_advantages.col(0) = batch.cost_advantages;
  cost_advantages.col(1) = batch.advantages.reverse() - batch.cost_advantages;
  PolicySurrogate surrogate(batch.observations, batch.actions, batch.old_log_probs, batch.advantages, cost_advantages);
  RunConfig config = sgd_config();
  config.constraints = {{{"cost_outside_bounds"}, 25.0}, {{"cost_velocity_violation"}, 5.0}};
  const std::vector<ConstraintEstimate> constraints = {{30.0, 25.0}, {3.0, 5.0}};
  PolicyUpdateInputs inputs = testing::inputs_for(batch, surrogate, 30.0, 100.0);
  inputs.constraints = constraints;
  Rcpo rcpo(config);
  const PolicyUpdateResult result = rcpo.update(inputs);
  // lambda_1 = 0.001 + 0.05 * 5 = 0.251; lambda_2 = max(0, 0.001 + 0.05 * (3 - 5)) = 0.
  EXPECT_NEAR(result.value("constraint_1_lambda"), 0.251, 1e-15);
  EXPECT_EQ(result.value("constraint_2_lambda"), 0.0);
  // Loss/Pi at theta_old (rho = 1): -mean(A - 0.251 A^C1) / 1.251.
  EXPECT_NEAR(result.value("Loss/Pi"), -(batch.advantages - 0.251 * cost_advantages.col(0)).mean() / 1.251, 1e-12);
}

TEST(Rcpo, ShippedDefaultsAndRefusedKeys) {
  const RunConfig shipped = resolve_run_config(testing::shipped_request("SafetyBallCircle-v0", "rcpo", {})).config;
  EXPECT_EQ(shipped.multiplier.lambda_optimizer, LambdaOptimizer::adam);  // OmniSafe's RCPO.yaml
  EXPECT_EQ(shipped.multiplier.lambda_lr, 0.035);
  EXPECT_EQ(shipped.trust_region.cg_iters, 15);
  EXPECT_EQ(shipped.trust_region.fvp_subsample, 1);
  EXPECT_TRUE(shipped.use_cost_value_function);
  for (const std::string& setting : std::vector<std::string>{"backtrack_budget=10", "backtrack_decay=0.5", "kl_accept_factor=2", "clip=0.2",
                                    "actor_lr=0.001", "p3o_kappa=1"}) {
    SCOPED_TRACE(setting);
    const std::string m = testing::config_error_of(testing::shipped_request("SafetyBallCircle-v0", "rcpo", {setting}));
    const std::string key = setting.substr(0, setting.find('='));
    EXPECT_TRUE(testing::contains(m, "'" + key + "' does not apply to alg 'rcpo'")) << m;
    EXPECT_EQ(m.find('\n'), std::string::npos) << m;
  }
  // The PID rule is a multiplier rule like the others: RCPO-PID.
  EXPECT_EQ(resolve_run_config(testing::shipped_request("SafetyBallCircle-v0", "rcpo", {"lambda_optimizer=PID"}))
                .config.multiplier.lambda_optimizer,
            LambdaOptimizer::pid);
}

}  // namespace
}  // namespace bsg::algos
