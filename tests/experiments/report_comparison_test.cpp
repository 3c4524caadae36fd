// `bsg table --compare report`: the shipped transcription of the report's
// Table 1 (spot values read off the report by hand), and a hand-built
// Table 1 set beside it with differences worked out by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "../test_support.h"
#include "experiments/report_comparison.h"

namespace fs = std::filesystem;

namespace {

const fs::path kReport = fs::path(BSG_SOURCE_DIR) / "configs" / bsg::experiments::kReportTable1File;

bsg::experiments::Table1Cell cell(bsg::Algorithm alg, double mean_return, double mean_cost) {
  bsg::experiments::Table1Cell c;
  c.alg = alg;
  c.selected = true;
  c.score.mean_return = mean_return;
  c.score.mean_cost = mean_cost;
  return c;
}

}  // namespace

TEST(ReportTable1, TheShippedTranscriptionHasEveryCellAndTheReportsValues) {
  const bsg::experiments::ReportTable1 report = bsg::experiments::load_report_table1(kReport);
  EXPECT_EQ(report.size(), 80u);  // 16 environments x 5 algorithms
  EXPECT_DOUBLE_EQ(report.at({"SafetyAntRun-v0", "trpo"}).h_ratio, 38.9);
  EXPECT_DOUBLE_EQ(report.at({"SafetyCarReach-v0", "pcpo"}).j_ratio, 0.00);
  EXPECT_DOUBLE_EQ(report.at({"SafetyCarReach-v0", "pcpo"}).h_ratio, 1.14);
  EXPECT_DOUBLE_EQ(report.at({"SafetyDroneCircle-v0", "pdo"}).j_ratio, 0.80);
  EXPECT_DOUBLE_EQ(report.at({"SafetyDroneCircle-v0", "pdo"}).h_ratio, 0.56);
  EXPECT_DOUBLE_EQ(report.at({"SafetyBallGather-v0", "lag-trpo"}).h_ratio, 1.09);
  for (const auto& [key, value] : report) EXPECT_DOUBLE_EQ(key.second == "trpo" ? value.j_ratio : 1.0, 1.0) << key.first;
}

TEST(ReportTable1, EachCellBesideTheReportsAndTheDifference) {
  bsg::experiments::Table1 table;
  table.columns = {{bsg::Algorithm::trpo, false}, {bsg::Algorithm::lag_trpo, false}};
  bsg::experiments::Table1Row row;
  row.env_id = "SafetyBallCircle-v0";
  row.cost_limit = 25.0;
  row.cells = {cell(bsg::Algorithm::trpo, 100.0, 50.0), cell(bsg::Algorithm::lag_trpo, 48.0, 20.0)};
  table.rows.push_back(row);
  const bsg::experiments::ReportTable1 report = bsg::experiments::load_report_table1(kReport);
  // TRPO: J 1 vs 1.00, H 50/25 = 2 vs 3.19; TRPO-L: 0.48 vs 0.96, 0.8 vs 0.97.
  EXPECT_EQ(bsg::experiments::comparison_csv(table, report),
            "env_id,alg,ours_j_ratio,report_j_ratio,j_ratio_diff,ours_h_ratio,report_h_ratio,h_ratio_diff\n"
            "SafetyBallCircle-v0,trpo,1,1,0,2,3.19,-1.19\n"
            "SafetyBallCircle-v0,lag-trpo,0.48,0.96,-0.48,0.8,0.97,-0.17\n");
  const std::string markdown = bsg::experiments::comparison_markdown(table, report);
  EXPECT_NE(markdown.find("| BallCircle | J/J_TRPO | 1.00 / 1.00 (+0.00) | 0.48 / 0.96 (-0.48) |"), std::string::npos)
      << markdown;
  EXPECT_NE(markdown.find("|  | H/d | 2.00 / 3.19 (-1.19) | 0.80 / 0.97 (-0.17) |"), std::string::npos) << markdown;
}

TEST(ReportTable1, AMalformedFileIsNamedWithItsLine) {
  bsg::testing::TemporaryDirectory temp;
  const fs::path path = temp.path() / "t.csv";
  std::ofstream(path) << "# comment\nenv_id,alg,j_ratio,h_ratio\nSafetyBallCircle-v0,trpo,1.00,x\n";
  try {
    bsg::experiments::load_report_table1(path);
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("line 3"), std::string::npos) << e.what();
  }
}
