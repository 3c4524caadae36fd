// `bsg train` finds its configs from anywhere: near the run file, near the
// current folder, in $BSG_CONFIGS, in the source tree (the installed configs
// are tested on a real install by tests/install/), or where --configs says;
// --print-config and the training header say which folder was used, and a
// bad $BSG_CONFIGS is an error listing the places tried.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "../test_support.h"
#include "run_bsg.h"

namespace fs = std::filesystem;
using bsg::testing::contains;
using bsg::testing::read_text_file;
using bsg::testing::run_bsg_in;
using bsg::testing::TemporaryDirectory;
using bsg::testing::write_text_file;

namespace {

const fs::path kShippedConfigs = fs::path(BSG_SOURCE_DIR) / "configs";
constexpr const char* kNoVariable = "-u BSG_CONFIGS";

// A copy of the shipped algorithms/ and envs/ at `dir`.
fs::path copy_configs(const fs::path& dir) {
  fs::create_directories(dir);
  for (const char* folder : {"algorithms", "envs"}) {
    fs::copy(kShippedConfigs / folder, dir / folder, fs::copy_options::recursive);
  }
  return dir;
}

std::string first_line(const std::string& text) { return text.substr(0, text.find('\n')); }

class ConfigsFromAnywhere : public ::testing::Test {
 protected:
  void SetUp() override {
    for (const fs::path& ancestor : {root_.parent_path(), fs::path("/")}) {
      if (fs::is_directory(ancestor / "configs" / "algorithms")) {
        GTEST_SKIP() << (ancestor / "configs") << " is a configs folder above the scratch folder";
      }
    }
    for (const fs::path& folder : {loose_, elsewhere_, empty_}) fs::create_directories(folder);
    write_text_file(loose_ / "run.yaml", "env_id: SafetyBallCircle-v0\nalg: lag-trpo\n");
    copy_configs(elsewhere_ / "configs");
  }

  std::string print_config_from(const fs::path& cwd, const std::string& environment,
                                const std::string& run_file, int expected_exit = 0) {
    const auto result =
        run_bsg_in(cwd.string(), environment, "train " + run_file + " --print-config");
    EXPECT_EQ(result.exit_code, expected_exit) << result.output;
    return result.output;
  }

  const TemporaryDirectory scratch_{"configs_search_test"};
  const fs::path root_ = scratch_.path();
  const fs::path loose_ = root_ / "loose";          // run.yaml, no configs at or above
  const fs::path elsewhere_ = root_ / "elsewhere";  // configs/ of its own
  const fs::path empty_ = root_ / "empty";          // nothing
};

TEST_F(ConfigsFromAnywhere, TheRunFilesProjectComesFirst) {
  const fs::path project = root_ / "project";
  copy_configs(project / "configs");
  fs::create_directories(project / "runs");
  write_text_file(project / "runs" / "run.yaml", "env_id: SafetyBallCircle-v0\nalg: lag-trpo\n");
  const std::string output =
      print_config_from(elsewhere_, "BSG_CONFIGS=" + elsewhere_.string() + "/configs",
                        (project / "runs" / "run.yaml").string());
  EXPECT_EQ(first_line(output), "# configs: " + (project / "configs").string() +
                                    " (at or above the run file's folder)");
}

TEST_F(ConfigsFromAnywhere, ThenTheCurrentFolderThenTheVariableThenTheSourceTree) {
  const std::string run_file = (loose_ / "run.yaml").string();
  EXPECT_EQ(
      first_line(print_config_from(elsewhere_, kNoVariable, run_file)),
      "# configs: " + (elsewhere_ / "configs").string() + " (at or above the current folder)");
  // A relative run file is found from the current folder too.
  EXPECT_EQ(first_line(print_config_from(root_, kNoVariable, "loose/run.yaml")),
            "# configs: " + kShippedConfigs.string() + " (the source tree's configs)");

  // $BSG_CONFIGS, with a changed value that shows its files are the ones read.
  const fs::path variable = copy_configs(root_ / "variable");
  write_text_file(variable / "envs" / "SafetyBallCircle-v0.yaml",
                  "cost_limit: 3.5\nepochs: 7\nsteps_per_epoch: 1000\nmax_ep_len: 250\n");
  const std::string output =
      print_config_from(empty_, "BSG_CONFIGS=" + variable.string(), run_file);
  EXPECT_EQ(first_line(output), "# configs: " + variable.string() + " ($BSG_CONFIGS)");
  EXPECT_TRUE(contains(output, "cost_limit: 3.5"));
  EXPECT_TRUE(contains(output, "epochs: 7"));

  EXPECT_EQ(first_line(print_config_from(empty_, kNoVariable, run_file)),
            "# configs: " + kShippedConfigs.string() + " (the source tree's configs)");
}

TEST_F(ConfigsFromAnywhere, TheConfigsOptionOverridesTheSearch) {
  const fs::path chosen = copy_configs(root_ / "chosen");
  const auto result = run_bsg_in(
      elsewhere_.string(), kNoVariable,
      "train " + (loose_ / "run.yaml").string() + " --print-config --configs " + chosen.string());
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_EQ(first_line(result.output), "# configs: " + chosen.string() + " (--configs)");
}

TEST_F(ConfigsFromAnywhere, ABadVariableIsAnErrorListingThePlacesTried) {
  const fs::path missing = root_ / "no_configs_here";
  const std::string output = print_config_from(empty_, "BSG_CONFIGS=" + missing.string(),
                                               (loose_ / "run.yaml").string(), 1);
  EXPECT_TRUE(contains(output, "$BSG_CONFIGS names " + missing.string()));
  EXPECT_TRUE(
      contains(output, "1. at or above the run file's folder: " + (loose_ / "configs").string() +
                           ", " + (root_ / "configs").string()));
  EXPECT_TRUE(
      contains(output, "2. at or above the current folder: " + (empty_ / "configs").string()));
  EXPECT_TRUE(contains(output, "3. $BSG_CONFIGS: " + missing.string()));
}

TEST_F(ConfigsFromAnywhere, TrainingSaysWhichFolderItUsed) {
  write_text_file(loose_ / "run.yaml",
                  "env_id: SafetyBallCircle-v0\nalg: lag-trpo\nepochs: 1\nsteps_per_epoch: 500\n"
                  "eval_episodes: 1\n");
  const auto result = run_bsg_in(elsewhere_.string(), kNoVariable,
                                 "train " + (loose_ / "run.yaml").string() + " --out run");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_TRUE(contains(result.output, "configs: " + (elsewhere_ / "configs").string() +
                                          " (at or above the current folder)"));
  EXPECT_TRUE(contains(read_text_file(elsewhere_ / "run" / "config.yaml"), "alg: lag-trpo"));
}

// `bsg sweep` searches the same places, starting from the grid file's folder.
TEST_F(ConfigsFromAnywhere, SweepSearchesTheSamePlacesFromTheGridFile) {
  fs::copy_file(kShippedConfigs / "grids" / "quick.yaml", loose_ / "grid.yaml");
  const std::string sweep =
      "sweep " + (loose_ / "grid.yaml").string() + " --dry-run --out " + (root_ / "q").string();

  const fs::path missing = root_ / "no_configs_here";
  auto result = run_bsg_in(empty_.string(), "BSG_CONFIGS=" + missing.string(), sweep);
  EXPECT_EQ(result.exit_code, 1) << result.output;
  EXPECT_TRUE(contains(result.output,
                       "1. at or above the grid file's folder: " + (loose_ / "configs").string()));
  EXPECT_TRUE(contains(result.output, "$BSG_CONFIGS names " + missing.string()));

  const fs::path variable = copy_configs(root_ / "variable");
  result = run_bsg_in(empty_.string(), "BSG_CONFIGS=" + variable.string(), sweep);
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_TRUE(contains(result.output, "4 runs of 2 configurations"));
}

}  // namespace
