// The budget methods' shipped files (configs/algorithms/{ppo,trpo}-{saute,early-terminated,simmer}.yaml):
// each is its base algorithm's file with the budget keys, OmniSafe's Saute and Simmer defaults.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "common/run_config_resolve.h"

namespace bsg {
namespace {

RunConfig shipped(const std::string& alg) {
  RunConfigRequest request;
  request.configs_dir = std::filesystem::path(BSG_SOURCE_DIR) / "configs";
  request.set_arguments = {"alg=" + alg, "env_id=SafetyBallCircle-v0"};
  return resolve_run_config(request).config;
}

TEST(BudgetKeys, EachBudgetMethodIsItsBaseAlgorithmWithOmniSafesDefaults) {
  const struct {
    const char* method;
    const char* base;
  } pairs[] = {{"ppo-saute", "ppo"}, {"trpo-saute", "trpo"}, {"ppo-early-terminated", "ppo"},
               {"trpo-early-terminated", "trpo"}, {"ppo-simmer", "ppo"}, {"trpo-simmer", "trpo"}};
  for (const auto& pair : pairs) {
    SCOPED_TRACE(pair.method);
    RunConfig config = shipped(pair.method);
    EXPECT_EQ(config.budget.saute_gamma, 0.999);  // OmniSafe's PPOSaute.yaml / TRPOSaute.yaml
    EXPECT_EQ(config.budget.unsafe_reward, -1.0);
    // OmniSafe's PPOSimmerPID.yaml / TRPOSimmerPID.yaml (control_cfgs; safety_budget = upper_budget).
    EXPECT_EQ(config.budget.simmer_kp, 0.0005);
    EXPECT_EQ(config.budget.simmer_ki, 0.00001);
    EXPECT_EQ(config.budget.simmer_kd, 0.0);
    EXPECT_EQ(config.budget.simmer_polyak, 0.995);
    EXPECT_EQ(config.budget.simmer_initial_budget_fraction, 1.0);
    const RunConfig base = shipped(pair.base);
    config.alg = base.alg;
    EXPECT_EQ(config, base);
  }
}

}  // namespace
}  // namespace bsg
