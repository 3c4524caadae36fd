// The `learner:` preset (common/learner_preset.h, docs/algorithms.md#quirk-switches):
// `corrected` turns on Q1, Q4, Q5, Q10 (CPO only), Q19 and Q20 over the shipped
// algorithm files; a switch named in the run file or with --set keeps its
// value; `faithful` and no preset resolve to the same configuration.
#include "common/learner_preset.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "../test_support.h"
#include "common/run_config_schema.h"
#include "shipped_request.h"

namespace bsg {
namespace {

using testing::config_error_of;
using testing::contains;
using testing::shipped_request;

RunConfig resolve(const std::string& alg, std::vector<std::string> sets) {
  return resolve_run_config(shipped_request("SafetyBallRun-v0", alg, std::move(sets))).config;
}

TEST(LearnerPreset, FaithfulIsTheDefaultAndChangesNothing) {
  const RunConfig plain = resolve("trpo", {});
  EXPECT_EQ(plain.learner, Learner::faithful);
  RunConfig faithful = resolve("trpo", {"learner=faithful"});
  EXPECT_EQ(faithful, plain);
  // The new switches' shipped values are the original's.
  EXPECT_FALSE(plain.consistent_return_statistic);
  EXPECT_FALSE(plain.rescale_value_output);
  EXPECT_EQ(plain.reward_scale_warmup_epochs, 0);
  EXPECT_TRUE(plain.timeout_bootstrap);
  EXPECT_FALSE(plain.center_advantages);
  EXPECT_FALSE(plain.value_time_input);
  EXPECT_EQ(plain.exploration_anneal_epochs, 0);
}

TEST(LearnerPreset, CorrectedTurnsOnEveryCorrectedSwitch) {
  const RunConfig trpo = resolve("trpo", {"learner=corrected"});
  EXPECT_EQ(trpo.learner, Learner::corrected);
  EXPECT_TRUE(trpo.zero_bias_init);               // Q1
  EXPECT_TRUE(trpo.exact_parallel_variance);      // Q4
  EXPECT_TRUE(trpo.consistent_return_statistic);  // Q5
  EXPECT_TRUE(trpo.rescale_value_output);         // Q19
  EXPECT_TRUE(trpo.value_time_input);             // Q20
  EXPECT_EQ(trpo.exploration_anneal_epochs, 0);   // a change of protocol, not a correction
  EXPECT_FALSE(trpo.center_advantages);           // a choice (Q6), not a correction
  EXPECT_EQ(trpo.trust_region.cpo_r_sign, CpoRSign::original);  // Q10 is CPO's only
  // Everything else as without the preset.
  RunConfig expected = resolve("trpo", {});
  expected.learner = Learner::corrected;
  expected.zero_bias_init = expected.exact_parallel_variance = true;
  expected.consistent_return_statistic = expected.rescale_value_output = true;
  expected.value_time_input = true;
  EXPECT_EQ(trpo, expected);

  const RunConfig cpo = resolve("cpo", {"learner=corrected"});
  EXPECT_EQ(cpo.trust_region.cpo_r_sign, CpoRSign::corrected);  // Q10
  EXPECT_TRUE(cpo.rescale_value_output);
}

TEST(LearnerPreset, AKeyNamedBesideThePresetKeepsItsValueAndOrigin) {
  // --set after or before the preset: the explicit key wins either way.
  for (const auto& sets : {std::vector<std::string>{"learner=corrected", "rescale_value_output=false"},
                           std::vector<std::string>{"rescale_value_output=false", "learner=corrected"}}) {
    const ResolvedRunConfig resolved = resolve_run_config(shipped_request("SafetyBallRun-v0", "trpo", sets));
    EXPECT_FALSE(resolved.config.rescale_value_output);
    EXPECT_TRUE(resolved.config.consistent_return_statistic);
    EXPECT_EQ(resolved.origins.at("rescale_value_output"), "--set rescale_value_output=false");
    EXPECT_TRUE(contains(resolved.origins.at("consistent_return_statistic"), "learner: corrected"));
  }
  // In a run file likewise.
  const std::filesystem::path run = std::filesystem::temp_directory_path() / "bsg_learner_preset_run.yaml";
  {
    std::ofstream out(run);
    out << "env_id: SafetyBallRun-v0\nalg: cpo\nlearner: corrected\ncpo_r_sign: original\n";
  }
  RunConfigRequest request;
  request.configs_dir = std::filesystem::path(BSG_SOURCE_DIR) / "configs";
  request.run_file = run;
  const RunConfig cpo = resolve_run_config(request).config;
  std::filesystem::remove(run);
  EXPECT_EQ(cpo.trust_region.cpo_r_sign, CpoRSign::original);
  EXPECT_TRUE(cpo.zero_bias_init);
}

TEST(LearnerPreset, ABadPresetNamesTheKeyTheValueAndTheChoices) {
  const std::string m = config_error_of(shipped_request("SafetyBallRun-v0", "trpo", {"learner=fixed"}));
  EXPECT_TRUE(contains(m, "'learner'"));
  EXPECT_TRUE(contains(m, "'fixed'"));
  EXPECT_TRUE(contains(m, "faithful"));
  EXPECT_TRUE(contains(m, "corrected"));
}

TEST(LearnerPreset, EverySettingIsASchemaKeyWithAValidValue) {
  for (const auto& [name, value] : corrected_learner_settings()) {
    const ConfigKey* key = find_config_key(name);
    ASSERT_NE(key, nullptr) << name;
    EXPECT_NE(key->default_source, ConfigLayer::run) << name;
  }
}

}  // namespace
}  // namespace bsg
