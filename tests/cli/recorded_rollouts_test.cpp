// The 16 standard environments play exactly as they did before they became
// descriptions: `bsg rollout --json` prints every recorded file byte for byte
// (tests/data/rollouts/README.md).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include "run_bsg.h"

namespace {

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(RecordedRollouts, EveryStandardIdPrintsItsRecordedRolloutsByteForByte) {
  const std::filesystem::path folder = std::filesystem::path(BSG_TEST_DATA_DIR) / "rollouts";
  const std::regex name(R"((Safety\w+-v0)_(random|zero)_seed(\d+)\.json)");
  std::set<std::string> ids;
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    std::smatch parts;
    const std::string file = entry.path().filename().string();
    if (!std::regex_match(file, parts, name)) continue;
    SCOPED_TRACE(file);
    const bsg::testing::ProgramResult result =
        bsg::testing::run_bsg("rollout --env " + parts[1].str() + " --policy " + parts[2].str() +
                              " --seed " + parts[3].str() + " --episodes 2 --json");
    ASSERT_EQ(result.exit_code, 0) << result.output;
    EXPECT_EQ(result.output, read_text(entry.path()));
    ids.insert(parts[1].str());
    ++files;
  }
  EXPECT_EQ(ids.size(), 16u);
  EXPECT_EQ(files, 64);  // 16 ids x 2 policies x 2 seeds
}

}  // namespace
