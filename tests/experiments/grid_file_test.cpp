// Parsing grid files: the accepted format (envs, seeds, fixed, algorithms
// with their fixed settings and axes) and every kind of bad input, each
// error naming the file, the line and the key at fault.
#include "experiments/grid_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "../test_support.h"
#include "common/config_error.h"

namespace bsg::experiments {
namespace {

using testing::contains;

// The ConfigError message of parsing `text` as grid "g.yaml" (fails the test if it parses).
std::string parse_error(const std::string& text) {
  try {
    parse_grid(text, "g.yaml");
  } catch (const ConfigError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no error for:\n" << text;
  return "";
}

const std::string kMinimal =
    "envs: [SafetyBallCircle-v0]\n"
    "seeds: [0]\n"
    "algorithms:\n"
    "  trpo:\n";

TEST(GridFile, ParsesEnvsSeedsFixedSettingsAndAxesInFileOrder) {
  const GridSpec grid = parse_grid(
      "description: a test grid\n"
      "envs: [SafetyBallCircle-v0, SafetyCarRun-v0]\n"
      "seeds: [3, 1]\n"
      "fixed: {epochs: 2, hidden_sizes: [32, 32]}\n"
      "algorithms:\n"
      "  lag-trpo:\n"
      "    fixed: {lambda_optimizer: Adam}\n"
      "    axes:\n"
      "      target_kl: [0.0001, 1e-3]\n"
      "      lambda_lr: [0.1]\n"
      "  trpo:\n",
      "g.yaml");
  EXPECT_EQ(grid.description, "a test grid");
  EXPECT_EQ(grid.env_ids, (std::vector<std::string>{"SafetyBallCircle-v0", "SafetyCarRun-v0"}));
  EXPECT_EQ(grid.seeds, (std::vector<std::int64_t>{3, 1}));
  ASSERT_EQ(grid.fixed.size(), 2u);
  EXPECT_EQ(grid.fixed[0].key, "epochs");
  EXPECT_EQ(grid.fixed[1].value_text, "[32, 32]");
  EXPECT_EQ(grid.fixed[1].name_text, "32x32");
  ASSERT_EQ(grid.algorithms.size(), 2u);
  EXPECT_EQ(grid.algorithms[0].alg, Algorithm::lag_trpo);
  EXPECT_EQ(grid.algorithms[1].alg, Algorithm::trpo);
  EXPECT_TRUE(grid.algorithms[1].axes.empty());
  const AlgorithmGrid& lag = grid.algorithms[0];
  ASSERT_EQ(lag.fixed.size(), 1u);
  EXPECT_EQ(lag.fixed[0].value_text, "Adam");
  ASSERT_EQ(lag.axes.size(), 2u);
  EXPECT_EQ(lag.axes[0].key, "target_kl");
  ASSERT_EQ(lag.axes[0].values.size(), 2u);
  EXPECT_EQ(lag.axes[0].values[0].name_text, "0.0001");  // as written
  EXPECT_EQ(lag.axes[0].values[1].name_text, "1e-3");
  EXPECT_EQ(lag.axes[0].values[1].origin, "g.yaml:9:27");
  EXPECT_EQ(lag.axes[1].key, "lambda_lr");
}

TEST(GridFile, UnknownTopLevelKeyIsNamedWithItsLine) {
  const std::string message = parse_error(kMinimal + "sedes: [1]\n");
  EXPECT_TRUE(contains(message, "g.yaml:5:1"));
  EXPECT_TRUE(contains(message, "unknown key 'sedes'"));
  EXPECT_TRUE(contains(message, "description, envs, seeds, fixed, algorithms"));
}

TEST(GridFile, UnknownConfigurationKeyIsNamedWithASuggestion) {
  const std::string message = parse_error(
      "envs: [SafetyBallCircle-v0]\nseeds: [0]\nalgorithms:\n  trpo:\n    axes:\n      target_kll: [0.1]\n");
  EXPECT_TRUE(contains(message, "g.yaml:6:7"));
  EXPECT_TRUE(contains(message, "unknown configuration key 'target_kll'"));
  EXPECT_TRUE(contains(message, "did you mean 'target_kl'"));
}

TEST(GridFile, UnknownKeyInsideAnAlgorithmIsNamed) {
  const std::string message =
      parse_error("envs: [SafetyBallCircle-v0]\nseeds: [0]\nalgorithms:\n  trpo:\n    axis: {}\n");
  EXPECT_TRUE(contains(message, "unknown key 'axis' in algorithm 'trpo'"));
  EXPECT_TRUE(contains(message, "valid keys: fixed, axes"));
}

TEST(GridFile, UnknownAlgorithmIsNamed) {
  const std::string message = parse_error("envs: [SafetyBallCircle-v0]\nseeds: [0]\nalgorithms:\n  cvpo:\n");
  EXPECT_TRUE(contains(message, "g.yaml:4:3"));
  EXPECT_TRUE(contains(message, "unknown algorithm 'cvpo'"));
  EXPECT_TRUE(contains(message, "trpo | lag-trpo | cpo | pdo | pcpo | ppo | ppo-lag | focops | cup"));
}

TEST(GridFile, KeyOfAnotherAlgorithmIsRejected) {
  const std::string message = parse_error(
      "envs: [SafetyBallCircle-v0]\nseeds: [0]\nalgorithms:\n  cpo:\n    axes: {lambda_lr: [0.1]}\n");
  EXPECT_TRUE(contains(message, "'lambda_lr' does not apply to algorithm 'cpo'"));
  EXPECT_TRUE(contains(message, "lag-trpo, pdo"));
}

TEST(GridFile, TopLevelFixedKeyMustApplyToSomeAlgorithm) {
  const std::string message = parse_error(kMinimal + "fixed: {lambda_lr: 0.1}\n");
  EXPECT_TRUE(contains(message, "fixed key 'lambda_lr' applies to none of the grid's algorithms"));
}

TEST(GridFile, KeysTheSweepSetsCannotBeSwept) {
  for (const std::string key : {"seed", "env_id", "alg", "log_dir"}) {
    const std::string message = parse_error(kMinimal + "fixed: {" + key + ": 1}\n");
    EXPECT_TRUE(contains(message, "key '" + key + "' cannot be set in a grid"));
  }
}

TEST(GridFile, BadValuesAreNamedWithKeyAndLine) {
  std::string message = parse_error(
      "envs: [SafetyBallCircle-v0]\nseeds: [0]\nalgorithms:\n  trpo:\n    axes: {target_kl: [0.01, -1]}\n");
  EXPECT_TRUE(contains(message, "target_kl"));
  EXPECT_TRUE(contains(message, "g.yaml:5:30"));
  message = parse_error(
      "envs: [SafetyBallCircle-v0]\nseeds: [0]\nalgorithms:\n  trpo:\n    axes: {target_kl: [0.01, 1e-2]}\n");
  EXPECT_TRUE(contains(message, "axis 'target_kl' lists the value 0.01 twice"));
  message = parse_error(
      "envs: [SafetyBallCircle-v0]\nseeds: [0]\nalgorithms:\n  trpo:\n    axes: {target_kl: []}\n");
  EXPECT_TRUE(contains(message, "must be a non-empty list"));
  message = parse_error(
      "envs: [SafetyBallCircle-v0]\nseeds: [0]\nalgorithms:\n  trpo:\n    axes: {target_kl: 0.01}\n");
  EXPECT_TRUE(contains(message, "must be a non-empty list"));
  message = parse_error(kMinimal + "fixed: {target_kl: [0.01, 0.1]}\n");
  EXPECT_TRUE(contains(message, "belongs under 'axes'"));
  message = parse_error(
      "envs: [SafetyBallCircle-v0]\nseeds: [0]\nalgorithms:\n  trpo:\n    fixed: {target_kl: 0.1}\n"
      "    axes: {target_kl: [0.01]}\n");
  EXPECT_TRUE(contains(message, "is both fixed and an axis"));
}

TEST(GridFile, EnvsSeedsAndAlgorithmsAreRequiredAndChecked) {
  EXPECT_TRUE(contains(parse_error("seeds: [0]\nalgorithms: {trpo: }\n"), "missing key 'envs'"));
  EXPECT_TRUE(contains(parse_error("envs: [SafetyBallCircle-v0]\nalgorithms: {trpo: }\n"),
                       "missing key 'seeds'"));
  EXPECT_TRUE(contains(parse_error("envs: [SafetyBallCircle-v0]\nseeds: [0]\n"), "missing key 'algorithms'"));
  EXPECT_TRUE(contains(parse_error("envs: []\nseeds: [0]\nalgorithms: {trpo: }\n"),
                       "'envs' must be a non-empty list"));
  EXPECT_TRUE(contains(parse_error("envs: [SafetyBallCircle-v0]\nseeds: [0, 0]\nalgorithms: {trpo: }\n"),
                       "'seeds' lists 0 twice"));
  EXPECT_TRUE(contains(parse_error("envs: [SafetyBallCircle-v0]\nseeds: [-1]\nalgorithms: {trpo: }\n"),
                       "seed"));
  EXPECT_TRUE(contains(parse_error("envs: [SafetyBallCircle-v0]\nseeds: [0]\nalgorithms: {}\n"),
                       "'algorithms' must map at least one algorithm"));
  EXPECT_TRUE(contains(parse_error("envs: [SafetyBallCircle-v0]\nseeds: [0]\nalgorithms: {trpo: , trpo: }\n"),
                       "appears twice"));
}

TEST(GridFile, MalformedYamlNamesTheFile) {
  const std::string message = parse_error("envs: [SafetyBallCircle-v0\nseeds: [0]\n");
  EXPECT_TRUE(contains(message, "g.yaml: malformed YAML"));
  EXPECT_TRUE(contains(parse_error("- a list\n- not a mapping\n"), "g.yaml: a grid file must be a mapping"));
}

TEST(GridFile, MissingFileIsNamed) {
  try {
    load_grid_file("/nonexistent/grid.yaml");
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_TRUE(contains(e.what(), "grid file not found: /nonexistent/grid.yaml"));
  }
}

TEST(GridFile, LoadsAFile) {
  const testing::TemporaryDirectory dir;
  const std::filesystem::path path = dir.path() / "grid.yaml";
  std::ofstream(path) << kMinimal << "  cpo:\n    axes: {lam_c: [0.5, 0.9]}\n";
  const GridSpec grid = load_grid_file(path);
  EXPECT_EQ(grid.source_name, path.string());
  ASSERT_EQ(grid.algorithms.size(), 2u);
  EXPECT_EQ(grid.algorithms[1].axes[0].values.size(), 2u);
}

}  // namespace
}  // namespace bsg::experiments
