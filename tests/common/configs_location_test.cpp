// Finding the configs folder: the order of the places searched, which one
// wins, and an error that lists every place and folder tried.
#include "common/configs_location.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "../test_support.h"
#include "common/config_error.h"

namespace bsg {
namespace {

namespace fs = std::filesystem;
using testing::contains;

// A folder that counts as a configs folder: it holds algorithms/.
fs::path make_configs(const fs::path& dir) {
  fs::create_directories(dir / "algorithms");
  return dir;
}

std::string error_of(const std::vector<ConfigsPlace>& places) {
  try {
    locate_configs_dir(places);
  } catch (const ConfigError& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected a ConfigError";
  return "";
}

class ConfigsSearch : public ::testing::Test {
 protected:
  // root/work/a/b/run.yaml is the run file, root/here/x the current folder.
  void SetUp() override {
    for (const fs::path& ancestor : {root_.parent_path(), fs::path("/")}) {
      if (is_configs_dir(ancestor / "configs")) {
        GTEST_SKIP() << (ancestor / "configs") << " is a configs folder above the scratch folder";
      }
    }
    fs::create_directories(run_folder_);
    testing::write_text_file(run_file_, "env_id: SafetyBallCircle-v0\nalg: trpo\n");
    fs::create_directories(current_);
  }

  ConfigsSearchInputs inputs() const {
    ConfigsSearchInputs in;
    in.input_file = run_file_;
    in.current_dir = current_;
    in.configs_variable = (root_ / "variable").string();
    in.installed_dir = root_ / "prefix" / "share" / "bsg" / "configs";
    in.source_dir = root_ / "source" / "configs";
    return in;
  }

  const testing::TemporaryDirectory scratch_{"configs_location_test"};
  const fs::path root_ = scratch_.path();
  const fs::path run_folder_ = root_ / "work" / "a" / "b";
  const fs::path run_file_ = run_folder_ / "run.yaml";
  const fs::path current_ = root_ / "here" / "x";
};

TEST_F(ConfigsSearch, PlacesComeInTheDocumentedOrder) {
  const std::vector<ConfigsPlace> places = configs_search_places(inputs());
  ASSERT_EQ(places.size(), 5u);
  EXPECT_EQ(places[0].description, "at or above the run file's folder");
  EXPECT_EQ(places[1].description, "at or above the current folder");
  EXPECT_EQ(places[2].description, "$BSG_CONFIGS");
  EXPECT_EQ(places[3].description, "the installed configs");
  EXPECT_EQ(places[4].description, "the source tree's configs");
  // Upward walks: <folder>/configs, then each parent's configs, to the root.
  ASSERT_GE(places[0].candidates.size(), 4u);
  EXPECT_EQ(places[0].candidates[0], run_folder_ / "configs");
  EXPECT_EQ(places[0].candidates[1], root_ / "work" / "a" / "configs");
  EXPECT_EQ(places[0].candidates[2], root_ / "work" / "configs");
  EXPECT_EQ(places[0].candidates.back(), fs::path("/configs"));
  EXPECT_EQ(places[1].candidates[0], current_ / "configs");
  EXPECT_EQ(places[1].candidates.back(), fs::path("/configs"));
  EXPECT_EQ(places[2].candidates, std::vector<fs::path>{root_ / "variable"});
  EXPECT_TRUE(places[2].required);
  EXPECT_FALSE(places[3].required);
  EXPECT_EQ(places[4].candidates, std::vector<fs::path>{root_ / "source" / "configs"});
}

TEST_F(ConfigsSearch, EachPlaceWinsOnlyWhenTheEarlierOnesHoldNoConfigs) {
  // Fill every place, then take them away from the front one by one.
  const fs::path near_run =
      make_configs(root_ / "work" / "a" / "configs");  // one level above the run file
  const fs::path near_current = make_configs(current_ / "configs");
  const fs::path variable = make_configs(root_ / "variable");
  const fs::path installed = make_configs(root_ / "prefix" / "share" / "bsg" / "configs");
  const fs::path source = make_configs(root_ / "source" / "configs");

  LocatedConfigs found = locate_configs_dir(configs_search_places(inputs()));
  EXPECT_EQ(found.dir, near_run);
  EXPECT_EQ(found.place, "at or above the run file's folder");

  fs::remove_all(near_run);
  found = locate_configs_dir(configs_search_places(inputs()));
  EXPECT_EQ(found.dir, near_current);
  EXPECT_EQ(found.place, "at or above the current folder");

  fs::remove_all(near_current);
  found = locate_configs_dir(configs_search_places(inputs()));
  EXPECT_EQ(found.dir, variable);
  EXPECT_EQ(found.place, "$BSG_CONFIGS");

  fs::remove_all(variable);
  ConfigsSearchInputs without_variable = inputs();
  without_variable.configs_variable.reset();
  found = locate_configs_dir(configs_search_places(without_variable));
  EXPECT_EQ(found.dir, installed);
  EXPECT_EQ(found.place, "the installed configs");

  fs::remove_all(installed);
  found = locate_configs_dir(configs_search_places(without_variable));
  EXPECT_EQ(found.dir, source);
  EXPECT_EQ(found.place, "the source tree's configs");
}

TEST_F(ConfigsSearch, TheRunFilesFolderBeatsTheCurrentFolderAboveIt) {
  // The run file lies below the current folder, each with its own configs.
  const fs::path outer = make_configs(root_ / "work" / "configs");
  const fs::path inner = make_configs(run_folder_ / "configs");
  ConfigsSearchInputs in = inputs();
  in.current_dir = root_ / "work";
  EXPECT_EQ(locate_configs_dir(configs_search_places(in)).dir, inner);
  in.input_file.clear();  // no run file: --set alone names the run
  EXPECT_EQ(locate_configs_dir(configs_search_places(in)).dir, outer);
}

TEST_F(ConfigsSearch, ExplicitFolderReplacesTheSearchAndMustBeAConfigsFolder) {
  make_configs(run_folder_ / "configs");
  const fs::path chosen = make_configs(root_ / "chosen");
  ConfigsSearchInputs in = inputs();
  in.explicit_dir = chosen;
  EXPECT_EQ(locate_configs_dir(configs_search_places(in)).dir, chosen);
  EXPECT_EQ(locate_configs_dir(configs_search_places(in)).place, "--configs");

  in.explicit_dir = root_ / "no_such_folder";
  const std::string m = error_of(configs_search_places(in));
  EXPECT_TRUE(contains(m, "--configs names " + (root_ / "no_such_folder").string()));
  EXPECT_TRUE(contains(m, "not a configs folder"));
}

TEST_F(ConfigsSearch, AVariableNamingNoConfigsFolderIsAnErrorNotAFallThrough) {
  make_configs(root_ / "prefix" / "share" / "bsg" / "configs");  // would be found next
  const std::string m = error_of(configs_search_places(inputs()));
  EXPECT_TRUE(contains(m, "$BSG_CONFIGS names " + (root_ / "variable").string()));
  EXPECT_TRUE(contains(m, "no algorithms/ folder"));
  // The places tried before it are listed too.
  EXPECT_TRUE(
      contains(m, "1. at or above the run file's folder: " + (run_folder_ / "configs").string()));
  EXPECT_TRUE(contains(m, "2. at or above the current folder: " + (current_ / "configs").string()));
  EXPECT_FALSE(contains(m, "the installed configs"));
}

TEST_F(ConfigsSearch, NothingFoundListsEveryPlaceAndFolderTried) {
  ConfigsSearchInputs in = inputs();
  in.configs_variable.reset();
  const std::vector<ConfigsPlace> places = configs_search_places(in);
  const std::string m = error_of(places);
  EXPECT_TRUE(contains(m, "no configs folder"));
  for (const ConfigsPlace& place : places) {
    EXPECT_TRUE(contains(m, place.description));
    for (const fs::path& candidate : place.candidates) EXPECT_TRUE(contains(m, candidate.string()));
  }
  EXPECT_TRUE(contains(m, "3. $BSG_CONFIGS: not set"));
  EXPECT_TRUE(
      contains(m, "4. the installed configs: " + (root_ / "prefix/share/bsg/configs").string()));
  EXPECT_TRUE(contains(m, "5. the source tree's configs: " + (root_ / "source/configs").string()));
  EXPECT_TRUE(contains(m, "--configs DIR"));
  EXPECT_TRUE(contains(m, "BSG_CONFIGS=DIR"));
}

TEST_F(ConfigsSearch, AFolderWithoutAlgorithmsIsNotAConfigsFolder) {
  fs::create_directories(run_folder_ / "configs" / "envs");  // envs/ alone does not count
  const fs::path source = make_configs(root_ / "source" / "configs");
  ConfigsSearchInputs in = inputs();
  in.configs_variable.reset();
  EXPECT_FALSE(is_configs_dir(run_folder_ / "configs"));
  EXPECT_EQ(locate_configs_dir(configs_search_places(in)).dir, source);
}

TEST_F(ConfigsSearch, RelativeInputsAreTakenFromTheCurrentProcessFolder) {
  const ConfigsPlace place = configs_at_or_above("relative/folder", "somewhere");
  EXPECT_EQ(place.candidates.front(), fs::current_path() / "relative" / "folder" / "configs");
  EXPECT_EQ(place.candidates.back(), fs::path("/configs"));
}

}  // namespace
}  // namespace bsg
