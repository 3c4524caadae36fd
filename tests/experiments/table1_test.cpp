// Table 1 from hand-made results: J / J_TRPO with H / d, the report's row
// order and labels, the best constrained algorithm in bold, infeasible
// fallbacks and incomplete or missing results marked, and the CSV and LaTeX
// forms.
#include "experiments/table1.h"

#include <gtest/gtest.h>

#include <cmath>

#include "../test_support.h"
#include "common/csv_text.h"
#include "experiments/table1_render.h"

namespace bsg::experiments {
namespace {

using testing::contains;

ConfigurationResults table1_config(const std::string& env, Algorithm alg, const std::string& name,
                            std::vector<SeedResult> seeds, std::size_t expected = 2, double d = 25.0) {
  ConfigurationResults results;
  results.env_id = env;
  results.alg = alg;
  results.config_name = name;
  results.cost_limit = d;
  results.seeds_expected = expected;
  results.seeds = std::move(seeds);
  return results;
}

// BallRun (listed first here, last in the report) and BallCircle.
std::vector<ConfigurationResults> table1_results() {
  const std::string circle = "SafetyBallCircle-v0";
  return {
      table1_config("SafetyBallRun-v0", Algorithm::trpo, "default", {{0, 10, 50, {}}, {1, 10, 50, {}}}),
      table1_config("SafetyBallRun-v0", Algorithm::cpo, "default", {}),  // nothing finished
      table1_config(circle, Algorithm::trpo, "target_kl=0.001", {{0, 100, 70, {}}, {1, 100, 90, {}}}),
      table1_config(circle, Algorithm::trpo, "target_kl=0.01", {{0, 200, 80, {}}, {1, 200, 80, {}}}),
      table1_config(circle, Algorithm::lag_trpo, "a", {{0, 190, 24, {}}, {1, 194, 24.5, {}}}),
      table1_config(circle, Algorithm::cpo, "a", {{0, 150, 20, {}}}),  // 1 of 2 seeds
      table1_config(circle, Algorithm::pdo, "a", {{0, 300, 30, {}}, {1, 300, 34, {}}}),
      table1_config(circle, Algorithm::pdo, "b", {{0, 250, 26, {}}, {1, 250, 28, {}}}),
  };
}

TEST(Table1, SelectsNormalisesAndOrdersRowsLikeTheReport) {
  const Table1 table = build_table1(table1_results(), SelectionScore::mean_return);
  EXPECT_EQ(table.columns, (std::vector<Table1Column>{{Algorithm::trpo, false},
                                                      {Algorithm::lag_trpo, false},
                                                      {Algorithm::cpo, false},
                                                      {Algorithm::pdo, false}}));
  ASSERT_EQ(table.rows.size(), 2u);
  EXPECT_EQ(table.rows[0].env_id, "SafetyBallCircle-v0");
  EXPECT_EQ(table.rows[1].env_id, "SafetyBallRun-v0");
  const Table1Row& circle = table.rows[0];
  EXPECT_EQ(circle.trpo_return(), 200.0);
  EXPECT_EQ(circle.cells[0].config_name, "target_kl=0.01");
  EXPECT_TRUE(circle.cells[1].best_constrained);
  EXPECT_EQ(circle.cells[3].config_name, "b");  // lowest violation
  EXPECT_FALSE(circle.cells[3].constraint_met);
  EXPECT_FALSE(table.rows[1].cells[2].selected);
  EXPECT_EQ(table.configurations.size(), 8u);

  const std::string markdown = table1_markdown(table);
  EXPECT_TRUE(contains(markdown, "| Env | TRPO | TRPO-L | CPO | PDO |\n|---|---|---|---|---|\n"));
  EXPECT_TRUE(contains(markdown, "| BallCircle | 1.00 (3.20) | **0.96 (0.97)** | 0.75 (0.80) [1/2] | "
                                 "1.25 (1.08)\u2020 |\n"));
  EXPECT_TRUE(contains(markdown, "| BallRun | 1.00 (2.00) | missing | missing | missing |\n"));
}

TEST(Table1, WithoutTrpoRawReturnsAreShown) {
  const Table1 table = build_table1({table1_config("SafetyBallReach-v0", Algorithm::cpo, "a", {{0, 12.5, 5, {}}},
                                            1, 10.0)},
                                    SelectionScore::mean_return);
  EXPECT_TRUE(contains(table1_markdown(table), "| BallReach | **J=12.5 (0.50)** |"));
}

TEST(Table1, BestConstrainedPrefersMeetingTheLimitThenReturnThenLowerCost) {
  const std::string env = "SafetyCarGather-v0";
  Table1 table = build_table1({table1_config(env, Algorithm::cpo, "a", {{0, 5, 0.1, {}}}, 1, 0.2),
                               table1_config(env, Algorithm::pdo, "a", {{0, 50, 0.3, {}}}, 1, 0.2)},
                              SelectionScore::mean_return);
  EXPECT_TRUE(table.rows[0].cells[0].best_constrained);
  table = build_table1({table1_config(env, Algorithm::cpo, "a", {{0, 5, 0.5, {}}}, 1, 0.2),
                        table1_config(env, Algorithm::pdo, "a", {{0, 50, 0.3, {}}}, 1, 0.2)},
                       SelectionScore::mean_return);
  EXPECT_TRUE(table.rows[0].cells[1].best_constrained);
}

TEST(Table1, CsvHasOneLinePerCellWithMissingFieldsEmpty) {
  const Table1 table = build_table1(table1_results(), SelectionScore::mean_return);
  const std::string csv = table1_csv(table);
  EXPECT_TRUE(contains(csv, "env_id,alg,status,config,config_dir,seeds_finished,seeds_expected,mean_return,"));
  EXPECT_TRUE(contains(csv, "SafetyBallCircle-v0,pdo,infeasible,b,SafetyBallCircle-v0/pdo/b,2,2,250.0,27.0,0.0,25.0,1.25,1.08,false,false,PDO\n"));
  EXPECT_TRUE(contains(csv, "SafetyBallRun-v0,cpo,missing,,,0,0,,,,25.0,,,,false,CPO\n"));
  const std::string all = configurations_csv(table);
  EXPECT_TRUE(contains(all, "SafetyBallCircle-v0,trpo,target_kl=0.001,2,2,100.0,80.0,0.0,25.0,false,100.0,false,TRPO\n"));
}

TEST(Table1, CsvCarriesTheMeanTrainingCostRateOverSeeds) {
  SeedResult first{0, 190, 24, {}, 0.01};
  SeedResult second{1, 194, 24.5, {}, 0.04};
  const Table1 table = build_table1({table1_config("SafetyBallCircle-v0", Algorithm::trpo, "t", {{0, 200, 80, {}, 0.5}}),
                                     table1_config("SafetyBallCircle-v0", Algorithm::lag_trpo, "a", {first, second})},
                                    SelectionScore::mean_return);
  const std::string csv = table1_csv(table);
  // (0.01 + 0.04) / 2 = 0.025 beside J = 192 and H = 24.25.
  EXPECT_TRUE(contains(csv, ",lag-trpo,feasible,a,SafetyBallCircle-v0/lag-trpo/a,2,2,192.0,24.25,0.025,25.0,"));
  EXPECT_TRUE(contains(csv, "mean_return,mean_cost,mean_cost_rate,cost_limit,"));
  EXPECT_TRUE(contains(configurations_csv(table), "SafetyBallCircle-v0,trpo,t,1,2,200.0,80.0,0.5,25.0,"));
  // A run from before the cost rate (NaN) leaves the field empty.
  const Table1 old = build_table1(
      {table1_config("SafetyBallCircle-v0", Algorithm::trpo, "t", {{0, 200, 80, {}, std::nan("")}})}, SelectionScore::mean_return);
  EXPECT_TRUE(contains(table1_csv(old), ",1,2,200.0,80.0,,25.0,"));
}

TEST(Table1, ConfigurationNamesWithCommasAreQuotedInCsv) {
  const Table1 table = build_table1(
      {table1_config("SafetyBallCircle-v0", Algorithm::trpo, "target_kl=0.001,lam_c=0.5", {{0, 1, 1, {}}}, 1)},
      SelectionScore::mean_return);
  const std::string csv = table1_csv(table);
  const std::string line = csv.substr(csv.find('\n') + 1, csv.find('\n', csv.find('\n') + 1) - csv.find('\n') - 1);
  const std::vector<std::string> fields = parse_csv_fields(line);
  ASSERT_EQ(fields.size(), 16u);
  EXPECT_EQ(fields[3], "target_kl=0.001,lam_c=0.5");
  EXPECT_EQ(fields[4], "SafetyBallCircle-v0/trpo/target_kl=0.001,lam_c=0.5");
}

TEST(Table1, LatexMarksBestInfeasibleAndMissing) {
  const std::string latex = table1_latex(build_table1(table1_results(), SelectionScore::mean_return));
  EXPECT_TRUE(contains(latex, "\\begin{tabular}{lcccc}"));
  EXPECT_TRUE(contains(latex, "BallCircle & 1.00 (3.20) & \\textbf{0.96 (0.97)} & 0.75 (0.80) [1/2] & "
                              "1.25 (1.08)$^\\dagger$ \\\\\n"));
  EXPECT_TRUE(contains(latex, "BallRun & 1.00 (2.00) & \\emph{missing}"));
}

TEST(Table1, RowLabels) {
  EXPECT_EQ(table1_row_label("SafetyDroneGather-v0"), "DroneGather");
  EXPECT_EQ(table1_column_label(Algorithm::lag_trpo), "TRPO-L");
  EXPECT_EQ(table1_column_label(Table1Column{Algorithm::lag_trpo, true}), "TRPO-PID");
  EXPECT_EQ(table1_column_label(Table1Column{Algorithm::pdo, true}), "PDO-PID");
}

TEST(Table1, PidMultiplierConfigurationsFormColumnsOfTheirOwn) {
  // TRPO-L with SGD and with PID on the same environment: selected apart. The
  // PID configuration has the higher return but would not displace SGD's
  // selection, nor SGD's it: each column holds its own best.
  const std::string circle = "SafetyBallCircle-v0";
  std::vector<ConfigurationResults> all = {
      table1_config(circle, Algorithm::trpo, "default", {{0, 200, 80, {}}}, 1),
      table1_config(circle, Algorithm::lag_trpo, "sgd", {{0, 150, 24, {}}}, 1),
      table1_config(circle, Algorithm::lag_trpo, "pid", {{0, 170, 25, {}}}, 1),
      table1_config(circle, Algorithm::pdo, "pid", {{0, 100, 40, {}}}, 1),
  };
  all[2].pid_multiplier = true;
  all[3].pid_multiplier = true;
  all[3].config_dir = "sweeps/pid/SafetyBallCircle-v0/pdo/pid";
  const Table1 table = build_table1(all, SelectionScore::mean_return);
  EXPECT_EQ(table.columns, (std::vector<Table1Column>{{Algorithm::trpo, false},
                                                      {Algorithm::lag_trpo, false},
                                                      {Algorithm::lag_trpo, true},
                                                      {Algorithm::pdo, true}}));
  const Table1Row& row = table.rows.at(0);
  EXPECT_EQ(row.cells[1].config_name, "sgd");
  EXPECT_EQ(row.cells[2].config_name, "pid");
  EXPECT_TRUE(row.cells[2].best_constrained);  // 170 / 200 within the limit beats 150 / 200
  EXPECT_EQ(row.cells[3].config_dir, "sweeps/pid/SafetyBallCircle-v0/pdo/pid");
  const std::string markdown = table1_markdown(table);
  EXPECT_TRUE(contains(markdown, "| Env | TRPO | TRPO-L | TRPO-PID | PDO-PID |\n")) << markdown;
  EXPECT_TRUE(contains(markdown, "| BallCircle | 1.00 (3.20) | 0.75 (0.96) | **0.85 (1.00)** | 0.50 (1.60)\u2020 |"))
      << markdown;
  EXPECT_TRUE(contains(table1_csv(table), "SafetyBallCircle-v0,lag-trpo,feasible,pid,SafetyBallCircle-v0/lag-trpo/pid,"
                                          "1,1,170.0,25.0,0.0,25.0,0.85,1.0,true,true,TRPO-PID\n"));
  EXPECT_TRUE(contains(configurations_csv(table), "SafetyBallCircle-v0,lag-trpo,sgd,1,1,150.0,24.0,0.0,25.0,true,150.0,true,TRPO-L\n"));
}

TEST(Table1, CorrectedLearnerConfigurationsFormColumnsAfterTheFaithfulOnes) {
  // A faithful and a corrected sweep of TRPO and TRPO-L on one environment:
  // each corrected column holds its own selection, after every faithful
  // column, and its J is normalised by the faithful TRPO's like every other
  // column's (by the corrected TRPO's only in a table without a faithful one).
  const std::string run = "SafetyBallRun-v0";
  std::vector<ConfigurationResults> all = {
      table1_config(run, Algorithm::trpo, "default", {{0, 400, 230, {}}}, 1),
      table1_config(run, Algorithm::lag_trpo, "a", {{0, 100, 60, {}}}, 1),
      table1_config(run, Algorithm::trpo, "default", {{0, 2000, 230, {}}}, 1),
      table1_config(run, Algorithm::lag_trpo, "a", {{0, 500, 20, {}}}, 1),
  };
  all[2].corrected_learner = true;
  all[3].corrected_learner = true;
  const Table1 table = build_table1(all, SelectionScore::mean_return);
  EXPECT_EQ(table.columns, (std::vector<Table1Column>{{Algorithm::trpo, false, false},
                                                      {Algorithm::lag_trpo, false, false},
                                                      {Algorithm::trpo, false, true},
                                                      {Algorithm::lag_trpo, false, true}}));
  const Table1Row& row = table.rows.at(0);
  EXPECT_EQ(row.trpo_return(), 400.0);
  EXPECT_EQ(row.trpo_return(true), 400.0);
  EXPECT_TRUE(row.cells[3].best_constrained);  // within the limit, against 60 / 25
  EXPECT_EQ(table1_column_label(Table1Column{Algorithm::lag_trpo, false, true}), "TRPO-L corrected");
  const std::string markdown = table1_markdown(table);
  // 100 / 400 = 0.25 with 60 / 25 = 2.40; 2000 / 400 = 5.00; 500 / 400 = 1.25 with 20 / 25 = 0.80.
  EXPECT_TRUE(contains(markdown, "| Env | TRPO | TRPO-L | TRPO corrected | TRPO-L corrected |\n")) << markdown;
  EXPECT_TRUE(contains(markdown, "| BallRun | 1.00 (9.20) | 0.25 (2.40)\u2020 | 5.00 (9.20) | **1.25 (0.80)** |"))
      << markdown;
  EXPECT_TRUE(contains(configurations_csv(table), "SafetyBallRun-v0,lag-trpo,a,1,1,500.0,20.0,0.0,25.0,true,500.0,true,"
                                                  "TRPO-L corrected\n"));

  // Only the corrected sweep: its own TRPO is the reference.
  const Table1 corrected_only = build_table1({all[2], all[3]}, SelectionScore::mean_return);
  EXPECT_EQ(corrected_only.rows.at(0).trpo_return(), std::nullopt);
  EXPECT_EQ(corrected_only.rows.at(0).trpo_return(true), 2000.0);
  EXPECT_TRUE(contains(table1_markdown(corrected_only), "| BallRun | 1.00 (9.20) | **0.25 (0.80)** |"));
}

TEST(Table1, FirstOrderColumnsCppoPidAndPpoAsAnUnconstrainedColumn) {
  // PPO, like TRPO, is judged without the limit ("unconstrained", no dagger)
  // and is never the best constrained cell; ppo-lag with PID is CPPO-PID.
  EXPECT_EQ(table1_column_label(Algorithm::ppo), "PPO");
  EXPECT_EQ(table1_column_label(Algorithm::focops), "FOCOPS");
  EXPECT_EQ(table1_column_label(Algorithm::cup), "CUP");
  const std::string circle = "SafetyBallCircle-v0";
  std::vector<ConfigurationResults> all = {
      table1_config(circle, Algorithm::trpo, "default", {{0, 200, 80, {}}}, 1),
      table1_config(circle, Algorithm::ppo, "default", {{0, 300, 90, {}}}, 1),
      table1_config(circle, Algorithm::ppo_lag, "default", {{0, 150, 24, {}}}, 1),
      table1_config(circle, Algorithm::ppo_lag, "pid", {{0, 160, 30, {}}}, 1),
      table1_config(circle, Algorithm::focops, "default", {{0, 120, 20, {}}}, 1),
      table1_config(circle, Algorithm::cup, "default", {{0, 180, 25, {}}}, 1),
  };
  all[3].pid_multiplier = true;
  const Table1 table = build_table1(all, SelectionScore::mean_return);
  const std::string markdown = table1_markdown(table);
  EXPECT_TRUE(contains(markdown, "| Env | TRPO | PPO | PPO-Lag | CPPO-PID | FOCOPS | CUP |\n")) << markdown;
  // J and H relative to TRPO's return and the limit; CPPO-PID's H = 30 / 25 breaks the limit.
  EXPECT_TRUE(contains(markdown, "| BallCircle | 1.00 (3.20) | 1.50 (3.60) | 0.75 (0.96) | 0.80 (1.20)\u2020 | "
                                 "0.60 (0.80) | **0.90 (1.00)** |"))
      << markdown;
  EXPECT_TRUE(contains(table1_csv(table), "SafetyBallCircle-v0,ppo,unconstrained,"));
}

}  // namespace
}  // namespace bsg::experiments
