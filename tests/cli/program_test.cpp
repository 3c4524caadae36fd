// The `bsg` program's top-level contract: help, version, exit code 2 for a
// malformed command line.
#include <gtest/gtest.h>

#include "run_bsg.h"

using bsg::testing::run_bsg;

TEST(Program, HelpListsUsageAndExitsZero) {
  const auto result = run_bsg("--help");
  EXPECT_EQ(result.exit_code, 0);
  EXPECT_NE(result.output.find("Usage"), std::string::npos) << result.output;
}

TEST(Program, VersionPrintsProjectVersion) {
  const auto result = run_bsg("--version");
  EXPECT_EQ(result.exit_code, 0);
  EXPECT_NE(result.output.find(std::string("bsg ") + BSG_VERSION_STRING), std::string::npos)
      << result.output;
}

TEST(Program, UnknownSubcommandIsAnErrorWithExitCodeTwo) {
  const auto result = run_bsg("frobnicate");
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_NE(result.output.find("frobnicate"), std::string::npos) << result.output;
}

TEST(Program, UnknownOptionIsAnErrorWithExitCodeTwo) {
  const auto result = run_bsg("--no-such-option");
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_NE(result.output.find("--no-such-option"), std::string::npos) << result.output;
}

TEST(Program, MissingSubcommandIsAnErrorWithExitCodeTwo) {
  const auto result = run_bsg("");
  EXPECT_EQ(result.exit_code, 2);
}
