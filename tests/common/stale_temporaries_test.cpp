// remove_stale_temporaries (common/atomic_file.h): the temporaries that killed
// writers leave behind are removed, and nothing a write may still be using,
// nor any other file, is touched.
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

#include "../test_support.h"
#include "common/atomic_file.h"

namespace fs = std::filesystem;
using bsg::testing::TemporaryDirectory;
using bsg::testing::write_text_file;

namespace {

// The pid of a child that has exited and been reaped: no process has it now
// (unless the kernel hands it out again within the test, which it does not
// do so soon: pids are allocated cyclically).
long dead_pid() {
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  int status = 0;
  ::waitpid(child, &status, 0);
  return child;
}

fs::path make_file(const fs::path& dir, const std::string& name, std::chrono::seconds age) {
  const fs::path path = dir / name;
  write_text_file(path, "partial");
  fs::last_write_time(path, fs::file_time_type::clock::now() - age);
  return path;
}

TEST(StaleTemporaries, OnlyOldTemporariesOfGoneWritersAndVeryOldOnesAreRemoved) {
  TemporaryDirectory dir;
  const std::string dead = std::to_string(dead_pid());
  const std::string alive = std::to_string(::getpid());
  using std::chrono::seconds;
  const fs::path dead_old = make_file(dir.path(), "checkpoint.bin.tmp." + dead + ".AbCdEf", seconds(120));
  const fs::path dead_fresh = make_file(dir.path(), "config.yaml.tmp." + dead + ".x1y2z3", seconds(0));
  const fs::path alive_old = make_file(dir.path(), "evaluation.json.tmp." + alive + ".QwErTy", seconds(120));
  const fs::path alive_ancient = make_file(dir.path(), "returns.csv.tmp." + alive + ".zzzzzz", seconds(2 * 86400));
  // Not temporaries of write_file_atomically: kept whatever their age.
  std::vector<fs::path> others;
  for (const char* name : {"notes.tmp.txt", "a.tmp.12.abc", "a.tmp.x12.abcdef", ".tmp.12.abcdef", "progress.csv",
                           "b.tmp.12.abcdefg"}) {
    others.push_back(make_file(dir.path(), name, seconds(3 * 86400)));
  }
  fs::create_directory(dir.path() / ("sub.tmp." + dead + ".AbCdEf"));  // a directory, not a file

  const std::vector<fs::path> removed = bsg::remove_stale_temporaries(dir.path());

  EXPECT_EQ(removed, (std::vector<fs::path>{dead_old, alive_ancient}));  // sorted by name
  EXPECT_FALSE(fs::exists(dead_old));
  EXPECT_FALSE(fs::exists(alive_ancient));
  EXPECT_TRUE(fs::exists(dead_fresh)) << "a write that may still be under way on another host";
  EXPECT_TRUE(fs::exists(alive_old)) << "its writer is running here";
  for (const fs::path& other : others) EXPECT_TRUE(fs::exists(other)) << other;
  EXPECT_TRUE(fs::is_directory(dir.path() / ("sub.tmp." + dead + ".AbCdEf")));
}

TEST(StaleTemporaries, TheAgesAreTheCallersToChoose) {
  TemporaryDirectory dir;
  const fs::path fresh = make_file(dir.path(), "a.yaml.tmp." + std::to_string(dead_pid()) + ".AbCdEf",
                                   std::chrono::seconds(5));
  EXPECT_TRUE(bsg::remove_stale_temporaries(dir.path()).empty());
  bsg::StaleTemporaryAges ages;
  ages.dead_writer_age = std::chrono::seconds(1);
  EXPECT_EQ(bsg::remove_stale_temporaries(dir.path(), ages), std::vector<fs::path>{fresh});
}

TEST(StaleTemporaries, AMissingDirectoryHasNone) {
  TemporaryDirectory dir;
  EXPECT_TRUE(bsg::remove_stale_temporaries(dir.path() / "absent").empty());
}

}  // namespace
