// locate_dataset: a file is taken as it is, a directory gives <env_id>.hdf5 from
// itself or one level down, and anything else is one line naming the problem.
#include "algos/training/dataset_location.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <stdexcept>
#include <string>

#include "../../test_support.h"

namespace bsg::algos {
namespace {

namespace fs = std::filesystem;
using bsg::testing::TemporaryDirectory;
using bsg::testing::write_text_file;

std::string located_error(const fs::path& location, const std::string& env_id) {
  try {
    locate_dataset(location, env_id);
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  return "";
}

TEST(DatasetLocation, AFileOrAMissingPathIsTakenAsItIs) {
  TemporaryDirectory directory("dataset_location");
  write_text_file(directory.path() / "mine.hdf5", "x");
  EXPECT_EQ(locate_dataset(directory.path() / "mine.hdf5", "SafetyBallCircle-v0"), directory.path() / "mine.hdf5");
  // The reader's own error names a missing file; the location does not guess.
  EXPECT_EQ(locate_dataset(directory.path() / "absent.hdf5", "SafetyBallCircle-v0"),
            directory.path() / "absent.hdf5");
}

TEST(DatasetLocation, ADirectoryGivesTheEnvironmentsFileFromItselfOrOneLevelDown) {
  TemporaryDirectory directory("dataset_location");
  fs::create_directories(directory.path() / "ball_circle_run");
  fs::create_directories(directory.path() / "car_circle_run");
  write_text_file(directory.path() / "ball_circle_run" / "SafetyBallCircle-v0.hdf5", "x");
  write_text_file(directory.path() / "car_circle_run" / "SafetyCarCircle-v0.hdf5", "x");
  write_text_file(directory.path() / "SafetyBallRun-v0.hdf5", "x");
  EXPECT_EQ(locate_dataset(directory.path(), "SafetyBallCircle-v0"),
            directory.path() / "ball_circle_run" / "SafetyBallCircle-v0.hdf5");
  EXPECT_EQ(locate_dataset(directory.path(), "SafetyCarCircle-v0"),
            directory.path() / "car_circle_run" / "SafetyCarCircle-v0.hdf5");
  EXPECT_EQ(locate_dataset(directory.path(), "SafetyBallRun-v0"), directory.path() / "SafetyBallRun-v0.hdf5");
  // A relative location comes back absolute, for config.yaml.
  const fs::path previous = fs::current_path();
  fs::current_path(directory.path());
  const fs::path located = locate_dataset("ball_circle_run/..", "SafetyBallRun-v0");
  fs::current_path(previous);
  EXPECT_EQ(located, directory.path() / "SafetyBallRun-v0.hdf5");
}

TEST(DatasetLocation, NoFileOrTwoFilesAreRefusedWithOneLine) {
  TemporaryDirectory directory("dataset_location");
  fs::create_directories(directory.path() / "a");
  fs::create_directories(directory.path() / "b" / "deeper");
  write_text_file(directory.path() / "b" / "deeper" / "SafetyBallCircle-v0.hdf5", "x");
  const std::string none = located_error(directory.path(), "SafetyBallCircle-v0");
  EXPECT_NE(none.find("a directory with no SafetyBallCircle-v0.hdf5 in it or in its subdirectories"),
            std::string::npos)
      << none;
  EXPECT_EQ(none.find('\n'), std::string::npos);

  write_text_file(directory.path() / "a" / "SafetyBallCircle-v0.hdf5", "x");
  write_text_file(directory.path() / "SafetyBallCircle-v0.hdf5", "x");
  const std::string two = located_error(directory.path(), "SafetyBallCircle-v0");
  EXPECT_NE(two.find("holds 2 files named SafetyBallCircle-v0.hdf5"), std::string::npos) << two;
  EXPECT_NE(two.find((directory.path() / "a" / "SafetyBallCircle-v0.hdf5").string()), std::string::npos) << two;
  EXPECT_EQ(two.find('\n'), std::string::npos);
}

}  // namespace
}  // namespace bsg::algos
