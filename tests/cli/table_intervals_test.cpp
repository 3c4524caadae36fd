// `bsg table --ci` and `--frontier` end to end on a tiny sweep over two cost
// limits (TRPO and TRPO-L on SafetyBallCircle-v0, 2 epochs of 500 steps, 2
// seeds): the frontier's points against the runs' own evaluation.json, every
// interval file, scripts/plot_curves.py --ci with a CSV beside every PNG, and
// clear errors for a sweep with one seed, missing runs and one limit.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "../test_support.h"
#include "common/csv_text.h"
#include "run_bsg.h"

namespace fs = std::filesystem;
using bsg::testing::read_text_file;
using bsg::testing::run_bsg;
using bsg::testing::run_command;
using bsg::testing::TemporaryDirectory;

namespace {

using bsg::testing::kSource;

void write(const fs::path& path, const std::string& text) {
  std::ofstream(path) << text;
}

// The tiny sweep over d in {5, 25}, run once for the tests below.
class TableIntervals : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    temp_ = new TemporaryDirectory();
    const fs::path grid = temp_->path() / "frontier.yaml";
    write(grid,
          "envs: [SafetyBallCircle-v0]\nseeds: [0, 1]\n"
          "fixed: {epochs: 2, steps_per_epoch: 500, eval_episodes: 2}\n"
          "algorithms:\n  trpo:\n  lag-trpo:\n    axes:\n      cost_limit: [5, 25]\n");
    sweep_ = temp_->path() / "sweep";
    const auto result = run_bsg("sweep " + grid.string() + " --jobs 2 --out " + sweep_.string() + " --configs " +
                                (kSource / "configs").string());
    sweep_output_ = result.output;
    sweep_exit_ = result.exit_code;
  }
  static void TearDownTestSuite() {
    delete temp_;
    temp_ = nullptr;
  }
  void SetUp() override { ASSERT_EQ(sweep_exit_, 0) << sweep_output_; }

  // A copy of the sweep to damage.
  static fs::path copy_of_sweep(const std::string& name) {
    const fs::path copy = temp_->path() / name;
    fs::copy(sweep_, copy, fs::copy_options::recursive);
    return copy;
  }

  static TemporaryDirectory* temp_;
  static fs::path sweep_;
  static std::string sweep_output_;
  static int sweep_exit_;
};

TemporaryDirectory* TableIntervals::temp_ = nullptr;
fs::path TableIntervals::sweep_;
std::string TableIntervals::sweep_output_;
int TableIntervals::sweep_exit_ = -1;

double evaluation_return(const fs::path& run_dir) {
  return nlohmann::json::parse(read_text_file(run_dir / "evaluation.json")).at("mean_return").get<double>();
}

std::vector<std::map<std::string, std::string>> csv_rows(const fs::path& path) {
  std::istringstream stream(read_text_file(path));
  std::string line;
  std::getline(stream, line);
  const std::vector<std::string> header = bsg::parse_csv_fields(line);
  std::vector<std::map<std::string, std::string>> rows;
  while (std::getline(stream, line)) {
    const std::vector<std::string> fields = bsg::parse_csv_fields(line);
    std::map<std::string, std::string> row;
    for (std::size_t i = 0; i < header.size() && i < fields.size(); ++i) row[header[i]] = fields[i];
    rows.push_back(row);
  }
  return rows;
}

TEST_F(TableIntervals, TheFrontierHasOnePointPerLimitWithTheSeedsMeanReturn) {
  const auto table = run_bsg("table " + sweep_.string() + " --frontier");
  ASSERT_EQ(table.exit_code, 0) << table.output;
  for (const char* file : {"intervals.csv", "aggregates.csv", "distinguishable.csv", "profiles.csv",
                                  "training_safety.csv", "curves.csv", "table1_ci.md", "frontier.csv"}) {
    EXPECT_TRUE(fs::is_regular_file(sweep_ / file)) << file;
  }
  const auto points = csv_rows(sweep_ / "frontier.csv");
  ASSERT_EQ(points.size(), 2u) << read_text_file(sweep_ / "frontier.csv");
  const std::string limits[] = {"5", "25"};
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(points[i].at("column"), "TRPO-L");
    EXPECT_EQ(std::stod(points[i].at("cost_limit")), std::stod(limits[i]));
    EXPECT_EQ(points[i].at("seeds"), "2");
    const fs::path config = sweep_ / "SafetyBallCircle-v0" / "lag-trpo" / ("cost_limit=" + limits[i]);
    const double expected = (evaluation_return(config / "seed=0") + evaluation_return(config / "seed=1")) / 2.0;
    EXPECT_NEAR(std::stod(points[i].at("mean_return")), expected, 1e-9 * (1.0 + std::abs(expected)));
    EXPECT_LE(std::stod(points[i].at("return_low")), std::stod(points[i].at("mean_return")));
    EXPECT_GE(std::stod(points[i].at("return_high")), std::stod(points[i].at("mean_return")));
  }
  EXPECT_NE(table.output.find("Cost-limit frontier"), std::string::npos) << table.output;
  // TRPO normalises: its selected configuration's J / J_TRPO has mean 1 over its seeds.
  bool trpo_seen = false;
  for (const auto& row : csv_rows(sweep_ / "intervals.csv")) {
    if (row.at("column") == "TRPO" && row.at("metric") == "J_over_trpo" && row.at("statistic") == "mean") {
      trpo_seen = true;
      EXPECT_NEAR(std::stod(row.at("point")), 1.0, 1e-12);
    }
  }
  EXPECT_TRUE(trpo_seen);
}

// The fraction of epochs whose mean episode cost exceeds d and the final
// cumulative cost, worked out from a run's progress.csv here.
std::pair<double, double> over_limit_and_cumulative(const fs::path& run_dir, double limit) {
  const auto rows = csv_rows(run_dir / "progress.csv");
  double over = 0.0;
  for (const auto& row : rows) over += std::stod(row.at("episode_cost_mean")) > limit ? 1.0 : 0.0;
  return {over / static_cast<double>(rows.size()), std::stod(rows.back().at("cumulative_cost"))};
}

TEST_F(TableIntervals, SafetyDuringTrainingIsTheSeedsMeanOfWhatTheirLogsSay) {
  ASSERT_EQ(run_bsg("table " + sweep_.string() + " --ci").exit_code, 0);
  const fs::path config = sweep_ / "SafetyBallCircle-v0" / "lag-trpo" / "cost_limit=5";
  const auto [over_0, cumulative_0] = over_limit_and_cumulative(config / "seed=0", 5.0);
  const auto [over_1, cumulative_1] = over_limit_and_cumulative(config / "seed=1", 5.0);
  std::size_t checked = 0;
  for (const auto& row : csv_rows(sweep_ / "training_safety.csv")) {
    if (row.at("config") != "cost_limit=5" || row.at("statistic") != "mean") continue;
    if (row.at("metric") == "epochs_over_limit") {
      EXPECT_NEAR(std::stod(row.at("point")), (over_0 + over_1) / 2.0, 1e-12);
      ++checked;
    }
    if (row.at("metric") == "cumulative_cost") {
      EXPECT_NEAR(std::stod(row.at("point")), (cumulative_0 + cumulative_1) / 2.0, 1e-9 * (1.0 + cumulative_0));
      ++checked;
    }
  }
  EXPECT_EQ(checked, 2u);
}

TEST_F(TableIntervals, PlotCurvesDrawsEveryFigureWithItsCsvBeside) {
  ASSERT_EQ(run_bsg("table " + sweep_.string() + " --ci").exit_code, 0);
  const fs::path plots = temp_->path() / "plots";
  const auto plot = run_command("/usr/bin/python3 " + (kSource / "scripts" / "plot_curves.py").string() + " " +
                                sweep_.string() + " --ci --out " + plots.string());
  ASSERT_EQ(plot.exit_code, 0) << plot.output;
  std::size_t pngs = 0;
  for (const auto& entry : fs::directory_iterator(plots)) {
    if (entry.path().extension() != ".png") continue;
    ++pngs;
    EXPECT_EQ(read_text_file(entry.path()).substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
    fs::path csv = entry.path();
    csv.replace_extension(".csv");
    EXPECT_TRUE(fs::is_regular_file(csv)) << "no CSV beside " << entry.path();
  }
  for (const char* name : {"SafetyBallCircle-v0_ci.png", "profiles.png", "aggregates.png",
                           "frontier_SafetyBallCircle-v0.png"}) {
    EXPECT_TRUE(fs::is_regular_file(plots / name)) << name << "\n" << plot.output;
  }
  EXPECT_EQ(pngs, 4u) << plot.output;
}

TEST_F(TableIntervals, ASweepWithOneSeedLeftIsAnErrorNamingTheNeed) {
  // Missing runs: the seed=1 evaluations are gone, one seed per configuration is left.
  const fs::path damaged = copy_of_sweep("one_seed");
  for (const auto& entry : fs::recursive_directory_iterator(damaged)) {
    if (entry.path().filename() == "evaluation.json" && entry.path().parent_path().filename() == "seed=1") {
      fs::remove(entry.path());
    }
  }
  const auto table = run_bsg("table " + damaged.string() + " --ci");
  EXPECT_EQ(table.exit_code, 1) << table.output;
  EXPECT_NE(table.output.find("no configuration has two finished seeds"), std::string::npos) << table.output;
  EXPECT_NE(table.output.find("needs at least 2"), std::string::npos) << table.output;
}

TEST_F(TableIntervals, AMissingRunIsNamedAndItsConfigurationLeftOutOfTheFrontier) {
  const fs::path damaged = copy_of_sweep("missing_run");
  fs::remove(damaged / "SafetyBallCircle-v0" / "lag-trpo" / "cost_limit=5" / "seed=1" / "evaluation.json");
  const auto table = run_bsg("table " + damaged.string() + " --ci");
  ASSERT_EQ(table.exit_code, 0) << table.output;
  EXPECT_NE(table.output.find("SafetyBallCircle-v0/lag-trpo/cost_limit=5: 1 finished seed(s); no interval"),
            std::string::npos)
      << table.output;
  // One limit is left for TRPO-L: --frontier refuses, naming the limits.
  const auto frontier = run_bsg("table " + damaged.string() + " --frontier");
  EXPECT_EQ(frontier.exit_code, 1) << frontier.output;
  EXPECT_NE(frontier.output.find("no cost-limit frontier"), std::string::npos) << frontier.output;
}

TEST_F(TableIntervals, BadBootstrapOptionsAreRefused) {
  EXPECT_NE(run_bsg("table " + sweep_.string() + " --ci --resamples 10").exit_code, 0);
  EXPECT_NE(run_bsg("table " + sweep_.string() + " --ci --confidence 1").exit_code, 0);
}

}  // namespace
