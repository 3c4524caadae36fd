// The first-order algorithms' configuration (docs/algorithms.md#first-order-updates):
// the shipped defaults (OmniSafe's), keys that belong to another family
// rejected naming the key, and bad values rejected naming the key and the
// valid range.
#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "../test_support.h"
#include "shipped_request.h"
#include "common/config_error.h"
#include "common/run_config_resolve.h"

namespace bsg {
namespace {

using testing::contains;

using testing::ball_circle_request;

TEST(FirstOrderConfig, ShippedDefaults) {
  for (const char* alg : {"ppo", "ppo-lag", "focops", "cup"}) {
    SCOPED_TRACE(alg);
    const RunConfig config = resolve_run_config(ball_circle_request(alg, {})).config;
    EXPECT_EQ(config.first_order.actor_lr, 3e-4);
    EXPECT_EQ(config.first_order.update_iters, 40);
    EXPECT_EQ(config.first_order.policy_minibatch_size, 64);
    EXPECT_EQ(config.trust_region.target_kl, 0.02);
    EXPECT_TRUE(config.first_order.kl_early_stop);
    EXPECT_EQ(config.first_order.max_grad_norm, 40.0);
    EXPECT_TRUE(config.first_order.learn_log_std);  // OmniSafe's learned log sigma (docs/algorithms.md#learned-log-sigma)
    EXPECT_EQ(config.first_order.learned_std_init, 0.509);
    EXPECT_TRUE(config.use_standardized_advantages);
    EXPECT_EQ(config.use_cost_value_function, std::string(alg) != "ppo");
    if (std::string(alg) != "ppo") {
      // PPO-Lag: TRPO-L's SGD rule at OmniSafe's rate (docs/algorithms.md#ppo-lag); FOCOPS and CUP: OmniSafe's Adam.
      EXPECT_EQ(config.multiplier.lambda_optimizer,
                std::string(alg) == "ppo-lag" ? LambdaOptimizer::sgd : LambdaOptimizer::adam);
      EXPECT_EQ(config.multiplier.lambda_lr, 0.035);
      EXPECT_EQ(config.multiplier.lagrangian_multiplier_init, 0.001);
    }
  }
  const RunConfig focops = resolve_run_config(ball_circle_request("focops", {})).config;
  EXPECT_EQ(focops.first_order.focops_lam, 1.5);
  EXPECT_EQ(focops.first_order.focops_eta, 0.02);
  EXPECT_EQ(focops.multiplier.lagrangian_upper_bound, 2.0);
  EXPECT_EQ(resolve_run_config(ball_circle_request("ppo", {})).config.first_order.clip, 0.2);
  EXPECT_EQ(resolve_run_config(ball_circle_request("cup", {})).config.first_order.clip, 0.2);
  // CPPO-PID is ppo-lag with the PID rule.
  EXPECT_EQ(resolve_run_config(ball_circle_request("ppo-lag", {"lambda_optimizer=PID"})).config.multiplier.lambda_optimizer,
            LambdaOptimizer::pid);
}

TEST(FirstOrderConfig, KeysOfTheOtherFamilyAreRejected) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"trpo", "clip=0.1"},          {"cpo", "actor_lr=0.001"},     {"lag-trpo", "update_iters=10"},
      {"pdo", "kl_early_stop=false"}, {"ppo", "cg_iters=5"},         {"ppo-lag", "backtrack_budget=3"},
      {"focops", "clip=0.3"},         {"cup", "focops_eta=0.1"},     {"ppo", "lambda_lr=0.1"},
      {"ppo", "focops_lam=2"},        {"focops", "fvp_subsample=2"}, {"cup", "kl_accept_factor=2"},
      {"lag-trpo", "lagrangian_upper_bound=2"}, {"ppo-lag", "lagrangian_upper_bound=2"},
      {"trpo", "learn_log_std=true"},  {"cpo", "learn_log_std=false"}, {"pcpo", "learned_std_init=0.5"}};
  for (const auto& [alg, setting] : cases) {
    SCOPED_TRACE(alg + " " + setting);
    const std::string m = testing::config_error_of(ball_circle_request(alg, {setting}));
    const std::string key = setting.substr(0, setting.find('='));
    EXPECT_TRUE(contains(m, "'" + key + "' does not apply to alg '" + alg + "'")) << m;
  }
}

TEST(FirstOrderConfig, OutOfRangeValuesAreRejectedNamingTheKey) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"actor_lr=0", "(0, inf)"},           {"update_iters=0", "[1, 10000]"},
      {"policy_minibatch_size=0", "[1, "}, {"max_grad_norm=-1", "[0, inf)"},
      {"clip=1", "(0, 1)"},                {"clip=0", "(0, 1)"},
      {"kl_early_stop=maybe", "true or false"}, {"update_iters=2.5", "an integer"},
      {"learn_log_std=maybe", "true or false"}, {"learned_std_init=0", "(0, inf)"},
      {"learned_std_init=-0.5", "(0, inf)"},    {"learned_std_init=inf", "(0, inf)"},
      {"learned_std_init=nan", "(0, inf)"}};
  for (const auto& [setting, valid] : cases) {
    SCOPED_TRACE(setting);
    const std::string m = testing::config_error_of(ball_circle_request("ppo-lag", {setting}));
    const std::string key = setting.substr(0, setting.find('='));
    EXPECT_TRUE(contains(m, "key '" + key + "'")) << m;
    EXPECT_TRUE(contains(m, valid)) << m;
  }
  for (const char* setting : {"focops_lam=0", "focops_eta=-0.1"}) {
    const std::string m = testing::config_error_of(ball_circle_request("focops", {setting}));
    EXPECT_TRUE(contains(m, "(0, inf)")) << m;
  }
  const std::string bound = testing::config_error_of(ball_circle_request("focops", {"lagrangian_upper_bound=-1"}));
  EXPECT_TRUE(contains(bound, "key 'lagrangian_upper_bound'") && contains(bound, "[0, inf)")) << bound;
  const std::string m = testing::config_error_of(
      ball_circle_request("ppo", {"constraints=[{terms: [cost_outside_bounds], limit: 20}, {terms: [cost_velocity_violation], limit: 5}]"}));
  EXPECT_TRUE(contains(m, "alg 'ppo' ignores cost")) << m;
}

}  // namespace
}  // namespace bsg
