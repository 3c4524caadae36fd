// The `constraints:` key (common/constraint_config.h, docs/algorithms.md#several-constraints):
// a list read from a run file or --set, written back to config.yaml and read
// again to the same list, absent by default (config.yaml as before the key),
// and every malformed list rejected with the key and the fault named.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "../test_support.h"
#include "shipped_request.h"
#include "common/config_error.h"
#include "common/run_config_resolve.h"
#include "common/run_config_yaml.h"

namespace bsg {
namespace {

namespace fs = std::filesystem;
using testing::contains;

const char* const kTwoConstraints =
    "constraints=[{terms: [cost_outside_bounds], limit: 20}, {terms: [cost_velocity_violation], limit: 5}]";

RunConfigRequest ball_run_request(const std::string& alg, std::vector<std::string> sets) {
  return testing::shipped_request("SafetyBallRun-v0", alg, std::move(sets));
}

using testing::config_error_of;

TEST(ConstraintConfig, AbsentByDefaultAndLeftOutOfTheResolvedYaml) {
  const RunConfig config = resolve_run_config(ball_run_request("cpo", {})).config;
  EXPECT_TRUE(config.constraints.empty());
  EXPECT_EQ(to_yaml(config).find("constraints"), std::string::npos);
  EXPECT_EQ(run_config_from_yaml(to_yaml(config), "round trip"), config);
}

TEST(ConstraintConfig, AListFromSetIsReadAndRoundTripsThroughTheYaml) {
  const RunConfig config = resolve_run_config(ball_run_request("cpo", {kTwoConstraints})).config;
  ASSERT_EQ(config.constraints.size(), 2u);
  EXPECT_EQ(config.constraints[0].terms, std::vector<std::string>{"cost_outside_bounds"});
  EXPECT_EQ(config.constraints[0].limit, 20.0);
  EXPECT_EQ(config.constraints[1].terms, std::vector<std::string>{"cost_velocity_violation"});
  EXPECT_EQ(config.constraints[1].limit, 5.0);
  EXPECT_EQ(run_config_from_yaml(to_yaml(config), "round trip"), config);
}

TEST(ConstraintConfig, ARunFileListWithSeveralTermsAndAll) {
  testing::TemporaryDirectory dir;
  const fs::path run = dir.path() / "run.yaml";
  testing::write_text_file(run,
                           "env_id: SafetyBallGather-v0\nalg: lag-trpo\nconstraints:\n"
                           "  - terms: [cost_gathered_bombs, cost_out_of_range]\n    limit: 2.5\n"
                           "  - terms: all\n    limit: 0\n");
  RunConfigRequest request;
  request.configs_dir = fs::path(BSG_SOURCE_DIR) / "configs";
  request.run_file = run;
  const RunConfig config = resolve_run_config(request).config;
  ASSERT_EQ(config.constraints.size(), 2u);
  EXPECT_EQ(config.constraints[0].terms_text(), "cost_gathered_bombs+cost_out_of_range");
  EXPECT_EQ(config.constraints[0].limit, 2.5);
  EXPECT_TRUE(config.constraints[1].sums_all_terms());
  EXPECT_EQ(config.constraints[1].limit, 0.0);
  EXPECT_EQ(run_config_from_yaml(to_yaml(config), "round trip"), config);
}

TEST(ConstraintConfig, MalformedListsAreRejectedNamingTheFault) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"constraints=[]", "empty list"},
      {"constraints=[{terms: [cost_outside_bounds], limit: -1}]", "negative limit -1"},
      {"constraints=[{terms: [cost_outside_bounds]}]", "has no 'limit'"},
      {"constraints=[{limit: 3}]", "has no 'terms'"},
      {"constraints=[{terms: [], limit: 3}]", "empty 'terms'"},
      {"constraints=[{terms: [all, cost_outside_bounds], limit: 3}]", "'all' beside other terms"},
      {"constraints=[{terms: [a, a], limit: 3}]", "'a' twice"},
      {"constraints=[{terms: [a], limit: 3, weight: 2}]", "unknown field 'weight'"},
      {"constraints=[{terms: [a], limit: lots}]", "not a number"},
      {"constraints=5", "is not a list"},
  };
  for (const auto& [set, fault] : cases) {
    SCOPED_TRACE(set);
    const std::string message = config_error_of(ball_run_request("cpo", {set}));
    EXPECT_TRUE(contains(message, "'constraints'"));
    EXPECT_TRUE(contains(message, fault));
  }
}

TEST(ConstraintConfig, SeveralConstraintsForTrpoAreRejectedBecauseItIgnoresCost) {
  const std::string message = config_error_of(ball_run_request("trpo", {kTwoConstraints}));
  EXPECT_TRUE(contains(message, "'constraints'"));
  EXPECT_TRUE(contains(message, "ignores cost"));
  // One constraint is allowed: it is what TRPO's policy is judged by.
  EXPECT_EQ(resolve_run_config(ball_run_request("trpo", {"constraints=[{terms: all, limit: 10}]"})).config.constraints.size(),
            1u);
}

}  // namespace
}  // namespace bsg
