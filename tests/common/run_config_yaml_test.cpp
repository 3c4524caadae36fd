// to_yaml -> load gives the same RunConfig for every algorithm, and loading
// a resolved config applies the same validation as the configs/ files.
#include "common/run_config_yaml.h"
#include "shipped_request.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "../test_support.h"
#include "common/config_error.h"
#include "common/run_config_resolve.h"
#include "shipped_request.h"

namespace bsg {
namespace {

using testing::contains;

namespace fs = std::filesystem;

using testing::kShippedConfigs;

RunConfig shipped(const std::string& alg, const std::string& env_id,
                  std::vector<std::string> sets = {}) {
  RunConfigRequest request;
  request.configs_dir = kShippedConfigs;
  request.set_arguments = {"alg=" + alg, "env_id=" + env_id};
  request.set_arguments.insert(request.set_arguments.end(), sets.begin(), sets.end());
  return resolve_run_config(request).config;
}

std::string error_of_text(const std::string& text) {
  try {
    run_config_from_yaml(text, "resolved.yaml");
  } catch (const ConfigError& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected a ConfigError";
  return "";
}

std::string replace_line(std::string text, const std::string& key, const std::string& line) {
  const std::size_t start = text.find("\n" + key + ":");
  EXPECT_NE(start, std::string::npos) << key;
  const std::size_t end = text.find('\n', start + 1);
  return text.replace(start + 1, end - start - 1, line);
}

TEST(RunConfigYaml, RoundTripGivesAnEqualConfigForEveryAlgorithm) {
  for (const char* alg : {"trpo", "lag-trpo", "cpo", "pdo", "pcpo"}) {
    SCOPED_TRACE(alg);
    const RunConfig config = shipped(alg, "SafetyDroneGather-v0");
    EXPECT_EQ(run_config_from_yaml(to_yaml(config), "resolved.yaml"), config);
  }
}

TEST(RunConfigYaml, RoundTripKeepsNonDefaultValuesExactly) {
  const RunConfig cpo = shipped("cpo", "SafetyCarReach-v0",
                                {"seed=4294967295", "target_kl=0.000123456789",
                                 "gamma=0.3333333333333333", "hidden_sizes=[32, 16, 8]",
                                 "cpo_r_sign=corrected", "cpo_clamp_a=true",
                                 "log_dir='my runs/x: y'", "use_standardized_obs=false",
                                 "cost_limit=0.2"});
  ASSERT_EQ(cpo.log_dir, "my runs/x: y");
  const RunConfig back = run_config_from_yaml(to_yaml(cpo), "resolved.yaml");
  EXPECT_EQ(back, cpo);
  EXPECT_EQ(back.trust_region.target_kl, 0.000123456789);
  EXPECT_EQ(back.gamma, 0.3333333333333333);
  EXPECT_EQ(back.trust_region.cpo_r_sign, CpoRSign::corrected);

  const RunConfig pdo = shipped("pdo", "SafetyAntRun-v0",
                                {"lambda_optimizer=SGD", "pdo_line_search=no", "lambda_lr=0.1"});
  EXPECT_EQ(run_config_from_yaml(to_yaml(pdo), "resolved.yaml"), pdo);
  const RunConfig pcpo = shipped("pcpo", "SafetyBallRun-v0", {"pcpo_projection=l2"});
  EXPECT_EQ(run_config_from_yaml(to_yaml(pcpo), "resolved.yaml"), pcpo);
}

TEST(RunConfigYaml, FileRoundTripThroughWriteAndLoad) {
  const testing::TemporaryDirectory dir;
  const fs::path file = dir.path() / "run_config.yaml";
  const RunConfig config = shipped("lag-trpo", "SafetyBallCircle-v0", {"seed=3"});
  write_run_config(config, file);
  EXPECT_EQ(load_resolved_run_config(file, list_config_env_ids(kShippedConfigs)), config);
}

TEST(RunConfigYaml, WritesOnlyTheKeysOfTheAlgorithmWithDescriptions) {
  const std::string trpo = to_yaml(shipped("trpo", "SafetyBallCircle-v0"));
  EXPECT_TRUE(contains(trpo, "\nalg: trpo  # "));
  EXPECT_TRUE(contains(trpo, "\ntarget_kl: 0.01  # delta"));
  EXPECT_TRUE(contains(trpo, "\nhidden_sizes: [64, 64]  # "));
  EXPECT_TRUE(contains(trpo, "\ncost_limit: 25.0  # "));
  EXPECT_EQ(trpo.find("lambda_lr"), std::string::npos);
  EXPECT_EQ(trpo.find("cpo_r_sign"), std::string::npos);
  const std::string lag = to_yaml(shipped("lag-trpo", "SafetyBallCircle-v0"));
  EXPECT_TRUE(contains(lag, "\nlambda_lr: 0.05  # "));
  EXPECT_TRUE(contains(lag, "\nlambda_optimizer: SGD  # "));
}

TEST(RunConfigYaml, LoadRequiresEveryKeyOfTheAlgorithm) {
  const std::string text = to_yaml(shipped("cpo", "SafetyBallCircle-v0"));
  const std::string without = replace_line(text, "cpo_r_sign", "# removed");
  EXPECT_TRUE(contains(error_of_text(without), "resolved.yaml: resolved config lacks key "
                                               "'cpo_r_sign'"));
  EXPECT_TRUE(contains(error_of_text(replace_line(text, "alg", "")), "lacks key 'alg'"));
}

TEST(RunConfigYaml, ARunWrittenBeforeTheDtypeKeyResumesInFloat64) {
  RunConfig config = shipped("lag-trpo", "SafetyBallCircle-v0");
  config.dtype = Dtype::float32;
  const std::string without = replace_line(to_yaml(config), "dtype", "# written before dtype existed");
  const RunConfig loaded = run_config_from_yaml(without, "resolved.yaml");
  EXPECT_EQ(loaded.dtype, Dtype::float64);  // such runs were trained in float64
  config.dtype = Dtype::float64;
  EXPECT_EQ(loaded, config);
}

TEST(RunConfigYaml, LoadValidatesLikeTheConfigFiles) {
  const std::string text = to_yaml(shipped("cpo", "SafetyBallCircle-v0"));
  std::string m = error_of_text(replace_line(text, "gamma", "gamma: 2.0"));
  EXPECT_TRUE(contains(m, "resolved.yaml:"));
  EXPECT_TRUE(contains(m, "'gamma' = 2.0 is out of range"));

  m = error_of_text(text + "lambda_lr: 0.1\n");
  EXPECT_TRUE(contains(m, "'lambda_lr' does not apply to alg 'cpo'"));

  m = error_of_text(text + "gammma: 0.9\n");
  EXPECT_TRUE(contains(m, "unknown key 'gammma'"));
  EXPECT_TRUE(contains(m, "valid keys:"));

  m = error_of_text("alg: [cpo\n");
  EXPECT_TRUE(contains(m, "resolved.yaml: malformed YAML"));

  try {
    run_config_from_yaml(replace_line(text, "env_id", "env_id: SafetyNope-v0"), "r.yaml",
                         {"SafetyBallCircle-v0"});
    ADD_FAILURE() << "unknown env_id accepted";
  } catch (const ConfigError& e) {
    EXPECT_TRUE(contains(e.what(), "unknown env_id 'SafetyNope-v0'"));
    EXPECT_TRUE(contains(e.what(), "valid env ids: SafetyBallCircle-v0"));
  }
}

TEST(RunConfigYaml, MissingResolvedFileNamesThePath) {
  const fs::path missing = fs::temp_directory_path() / "bsg_no_such_config.yaml";
  try {
    load_resolved_run_config(missing);
    ADD_FAILURE() << "missing file accepted";
  } catch (const ConfigError& e) {
    EXPECT_TRUE(contains(e.what(), missing.string()));
  }
}

}  // namespace
}  // namespace bsg
