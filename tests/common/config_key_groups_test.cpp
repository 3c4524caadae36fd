// The family groups of RunConfig (common/trust_region_keys.h, multiplier_keys.h,
// first_order_keys.h, off_policy_keys.h, ..., multi_agent_keys.h): a flat key of the table reaches its
// group's member, and only that member, when set and when written back; each
// group's keys keep their place in the one table.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cstddef>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "common/run_config.h"
#include "common/run_config_schema.h"

namespace bsg {
namespace {

// Sets `key` to `value` through the table; the result must differ from `expected_change`
// applied to a default RunConfig in nothing.
template <typename Change>
void expect_key_reaches(std::string_view key, const std::string& value, Change expected_change) {
  SCOPED_TRACE(std::string(key));
  const ConfigKey* entry = find_config_key(key);
  ASSERT_NE(entry, nullptr);
  RunConfig through_table;
  set_config_value(through_table, *entry, YAML::Load(value), "test");
  RunConfig expected;
  expected_change(expected);
  EXPECT_TRUE(through_table == expected);
  EXPECT_FALSE(through_table == RunConfig{});
  EXPECT_EQ(config_value_to_yaml(through_table, *entry), value);
}

TEST(ConfigKeyGroups, AFlatKeyReachesItsGroupsMemberOnly) {
  expect_key_reaches("cg_iters", "7", [](RunConfig& c) { c.trust_region.cg_iters = 7; });
  expect_key_reaches("target_kl", "0.02", [](RunConfig& c) { c.trust_region.target_kl = 0.02; });
  expect_key_reaches("cpo_r_sign", "corrected", [](RunConfig& c) { c.trust_region.cpo_r_sign = CpoRSign::corrected; });
  expect_key_reaches("crpo_tolerance", "0.5", [](RunConfig& c) { c.trust_region.crpo_tolerance = 0.5; });
  expect_key_reaches("lambda_optimizer", "PID",
                     [](RunConfig& c) { c.multiplier.lambda_optimizer = LambdaOptimizer::pid; });
  expect_key_reaches("pid_d_delay", "3", [](RunConfig& c) { c.multiplier.pid_d_delay = 3; });
  expect_key_reaches("kl_early_stop", "false", [](RunConfig& c) { c.first_order.kl_early_stop = false; });
  expect_key_reaches("focops_eta", "0.1", [](RunConfig& c) { c.first_order.focops_eta = 0.1; });
  expect_key_reaches("batch_size", "64", [](RunConfig& c) { c.off_policy.batch_size = 64; });
  expect_key_reaches("auto_alpha", "true", [](RunConfig& c) { c.off_policy.auto_alpha = true; });
  expect_key_reaches("cpq_sampled_actions", "4", [](RunConfig& c) { c.offline.cpq_sampled_actions = 4; });
  expect_key_reaches("bcq_pid_kd", "0.25", [](RunConfig& c) { c.offline.bcq_pid_kd = 0.25; });
  expect_key_reaches("coptidice_f_divergence", "kl",
                     [](RunConfig& c) { c.offline.coptidice_f_divergence = FDivergence::kl; });
  expect_key_reaches("unsafe_reward", "-0.2", [](RunConfig& c) { c.budget.unsafe_reward = -0.2; });
  expect_key_reaches("simmer_polyak", "0.5", [](RunConfig& c) { c.budget.simmer_polyak = 0.5; });
  expect_key_reaches("share_policy", "true", [](RunConfig& c) { c.multi_agent.share_policy = true; });
  // RunConfig's own keys are reached as before.
  expect_key_reaches("gamma", "0.9", [](RunConfig& c) { c.gamma = 0.9; });
  expect_key_reaches("hidden_sizes", "[8, 8]", [](RunConfig& c) { c.hidden_sizes = {8, 8}; });
}

TEST(ConfigKeyGroups, EachGroupsRowsKeepTheirPlaceInTheTable) {
  std::vector<std::string_view> keys;
  for (const ConfigKey& entry : run_config_schema()) keys.push_back(entry.key);
  auto position = [&](std::string_view key) {
    for (std::size_t i = 0; i < keys.size(); ++i) {
      if (keys[i] == key) return static_cast<long>(i);
    }
    ADD_FAILURE() << key << " is not in the table";
    return -1L;
  };
  // The runs of rows, each key followed by the next: RunConfig's leading rows, the trust-region
  // tools, the multipliers, the trust-region variants, the first-order, off-policy, offline,
  // budget and multi-agent rows, and RunConfig's trailing rows.
  const std::vector<std::pair<std::string_view, std::string_view>> seams = {
      {"value_time_input", "target_kl"},         {"kl_accept_factor", "lagrangian_multiplier_init"},
      {"pid_lambda_max", "cpo_r_sign"},          {"crpo_tolerance", "actor_lr"},
      {"learned_std_init", "num_envs"},          {"multiplier_window", "dataset"},
      {"coptidice_scalar_lr", "saute_gamma"},    {"simmer_initial_budget_fraction", "share_policy"},
      {"share_policy", "use_cost_value_function"}};
  for (const auto& [before, after] : seams) EXPECT_EQ(position(before) + 1, position(after)) << before;
  EXPECT_EQ(keys.front(), "env_id");
  EXPECT_EQ(keys.back(), "sampled_evaluation");
}

}  // namespace
}  // namespace bsg
