// A grid sweeps environment parameters like any other key: an axis of the
// run key `env` with one mapping per value (docs/environments.md#environment-descriptions).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "experiments/grid_expansion.h"

namespace bsg::experiments {
namespace {

const std::filesystem::path kShippedConfigs = std::filesystem::path(BSG_SOURCE_DIR) / "configs";

TEST(GridEnvAxis, EachValueIsOneRunWithThatEnvironmentParameter) {
  const GridSpec grid = parse_grid(
      "envs: [SafetyBallGather-v0]\nseeds: [0]\nfixed: {epochs: 2}\n"
      "algorithms:\n  trpo:\n    axes:\n      env: [{bombs: 4}, {bombs: 12, apples: 6}]\n",
      "g.yaml");
  const std::vector<GridRun> runs = expand_grid(grid);
  ASSERT_EQ(runs.size(), 2u);
  EXPECT_EQ(runs[0].relative_dir().generic_string(), "SafetyBallGather-v0/trpo/env=bombs4/seed=0");
  EXPECT_EQ(runs[1].config_name, "env=bombs12_apples6");
  const RunConfig second = resolve_grid_run(runs[1], kShippedConfigs, "g.yaml");
  EXPECT_EQ(second.env, (std::vector<std::pair<std::string, std::string>>{{"bombs", "12"}, {"apples", "6"}}));
  EXPECT_EQ(resolve_grid_run(runs[0], kShippedConfigs, "g.yaml").env,
            (std::vector<std::pair<std::string, std::string>>{{"bombs", "4"}}));
}

}  // namespace
}  // namespace bsg::experiments
