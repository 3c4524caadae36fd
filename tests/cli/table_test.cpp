// `bsg table` on hand-made sweep directories: the selection rule (feasible
// best return; the lowest violation, marked, when nothing is feasible),
// missing runs shown as missing and never as zero, the mean - std option,
// the files written, and errors naming the file at fault.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "../test_support.h"
#include "algos/training/run_directory.h"
#include "common/run_config_yaml.h"
#include "experiments/grid_expansion.h"
#include "experiments/sweep_manifest.h"
#include "experiments/sweep_results.h"
#include "run_bsg.h"

namespace fs = std::filesystem;
using bsg::testing::read_text_file;
using bsg::testing::run_bsg;
using bsg::testing::TemporaryDirectory;

namespace {

const fs::path kConfigs = fs::path(BSG_SOURCE_DIR) / "configs";

// A grid of 2 TRPO, 2 CPO and 2 PDO configurations x 2 seeds on BallCircle (d = 25).
const char* const kGrid =
    "envs: [SafetyBallCircle-v0]\n"
    "seeds: [0, 1]\n"
    "algorithms:\n"
    "  trpo: {axes: {target_kl: [0.001, 0.01]}}\n"
    "  cpo: {axes: {lam_c: [0.5, 0.9]}}\n"
    "  pdo: {axes: {lambda_lr: [0.01, 0.1]}}\n";

// Writes a finished run of `runs` below `sweep_dir`: config.yaml,
// evaluation.json, returns.csv.
void finish_run(const fs::path& sweep_dir, const std::vector<bsg::experiments::GridRun>& runs, const std::string& relative_dir,
                std::vector<double> returns, double mean_cost) {
    for (const bsg::experiments::GridRun& run : runs) {
      if (run.relative_dir().generic_string() != relative_dir) continue;
      const bsg::algos::RunDirectory directory(sweep_dir / run.relative_dir());
      fs::create_directories(directory.root);
      bsg::write_run_config(bsg::experiments::resolve_grid_run(run, kConfigs, "hand-made grid"), directory.config());
      double sum = 0;
      std::string lines;
      for (const double value : returns) {
        sum += value;
        lines += std::to_string(value) + "\n";
      }
      std::ofstream(directory.returns()) << lines;
      std::ofstream(directory.evaluation())
          << "{\n  \"mean_return\": " << sum / static_cast<double>(returns.size()) << ",\n  \"mean_cost\": "
          << mean_cost << ",\n  \"episodes\": " << returns.size() << ",\n  \"mean_length\": 250\n}\n";
      return;
    }
    FAIL() << "no run " << relative_dir;
}

class HandMadeSweep : public ::testing::Test {
 protected:
  void SetUp() override {
    runs_ = bsg::experiments::expand_grid(bsg::experiments::parse_grid(kGrid, "hand-made grid"));
    bsg::experiments::write_sweep_manifest(dir_.path(), runs_);
  }

  void finish(const std::string& relative_dir, std::vector<double> returns, double mean_cost) {
    finish_run(dir_.path(), runs_, relative_dir, std::move(returns), mean_cost);
  }

  TemporaryDirectory dir_;
  std::vector<bsg::experiments::GridRun> runs_;
};

TEST_F(HandMadeSweep, SelectsFeasibleBestFallsBackToLowestViolationAndShowsMissingRuns) {
  const std::string circle = "SafetyBallCircle-v0/";
  // TRPO: J_TRPO = 200 (target_kl=0.01), H/d = 4.
  finish(circle + "trpo/target_kl=0.001/seed=0", {100}, 10);
  finish(circle + "trpo/target_kl=0.001/seed=1", {100}, 10);
  finish(circle + "trpo/target_kl=0.01/seed=0", {200}, 100);
  finish(circle + "trpo/target_kl=0.01/seed=1", {200}, 100);
  // CPO: lam_c=0.5 has the higher return but H = 30 > 25; lam_c=0.9 is feasible.
  finish(circle + "cpo/lam_c=0.5/seed=0", {180}, 30);
  finish(circle + "cpo/lam_c=0.5/seed=1", {180}, 30);
  finish(circle + "cpo/lam_c=0.9/seed=0", {100}, 20);
  finish(circle + "cpo/lam_c=0.9/seed=1", {60}, 25);
  // PDO: both infeasible; lambda_lr=0.1 violates least; one of its seeds is missing.
  finish(circle + "pdo/lambda_lr=0.01/seed=0", {150}, 60);
  finish(circle + "pdo/lambda_lr=0.01/seed=1", {150}, 60);
  finish(circle + "pdo/lambda_lr=0.1/seed=0", {-40}, 35);

  const auto result = run_bsg("table " + dir_.path().string());
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("| Env | TRPO | CPO | PDO |"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("| BallCircle | 1.00 (4.00) | **0.40 (0.90)** | -0.20 (1.40)\u2020 [1/2] |"),
            std::string::npos)
      << result.output;

  const std::string csv = read_text_file(dir_.path() / "table1.csv");
  EXPECT_NE(csv.find("SafetyBallCircle-v0,cpo,feasible,lam_c=0.9,SafetyBallCircle-v0/cpo/lam_c=0.9,2,2,80.0,22.5,"),
            std::string::npos)
      << csv;
  EXPECT_NE(csv.find("SafetyBallCircle-v0,pdo,infeasible,lambda_lr=0.1,SafetyBallCircle-v0/pdo/lambda_lr=0.1,1,2,"),
            std::string::npos)
      << csv;
  EXPECT_NE(read_text_file(dir_.path() / "table1.tex").find("\\textbf{0.40 (0.90)}"),
            std::string::npos);
  EXPECT_NE(read_text_file(dir_.path() / "table1.md").find("**0.40 (0.90)**"), std::string::npos);
  // These hand-made evaluations have no cost_rate: its field is empty.
  EXPECT_NE(read_text_file(dir_.path() / "configurations.csv")
                .find("SafetyBallCircle-v0,cpo,lam_c=0.5,2,2,180.0,30.0,,25.0,false,180.0,false"),
            std::string::npos);
}

TEST_F(HandMadeSweep, AnAlgorithmWithoutFinishedRunsIsMissingNotZero) {
  finish("SafetyBallCircle-v0/trpo/target_kl=0.01/seed=0", {-10}, 100);
  // CPO's only finished run has a negative return and violates the limit; a
  // missing configuration scored as zero would win instead.
  finish("SafetyBallCircle-v0/cpo/lam_c=0.5/seed=0", {-5}, 40);
  const auto result = run_bsg("table " + dir_.path().string());
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("| BallCircle | 1.00 (4.00) [1/2] | **0.50 (1.60)\u2020 [1/2]** | missing |"),
            std::string::npos)
      << result.output;
  EXPECT_NE(
      read_text_file(dir_.path() / "table1.csv").find("SafetyBallCircle-v0,pdo,missing,,,0,0,,,"),
      std::string::npos);
}

TEST_F(HandMadeSweep, MeanMinusStdPrefersTheSteadierConfiguration) {
  finish("SafetyBallCircle-v0/trpo/target_kl=0.01/seed=0", {100}, 10);
  // lam_c=0.5: mean 60, std 50 -> 10; lam_c=0.9: mean 50, std 1 -> 49. Both feasible.
  finish("SafetyBallCircle-v0/cpo/lam_c=0.5/seed=0", {10, 110}, 10);
  finish("SafetyBallCircle-v0/cpo/lam_c=0.9/seed=0", {49, 51}, 10);
  auto result = run_bsg("table " + dir_.path().string());
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("**0.60 (0.40) [1/2]**"), std::string::npos) << result.output;
  result = run_bsg("table " + dir_.path().string() + " --score mean_minus_std");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("**0.50 (0.40) [1/2]**"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("Selection score: mean_minus_std"), std::string::npos) << result.output;
}

TEST_F(HandMadeSweep, RunDirectoriesWithoutAManifestAreFoundByTheirFiles) {
  finish("SafetyBallCircle-v0/trpo/target_kl=0.01/seed=0", {100}, 10);
  finish("SafetyBallCircle-v0/cpo/lam_c=0.9/seed=1", {50}, 10);
  fs::remove(dir_.path() / bsg::experiments::kSweepManifestName);
  const std::vector<bsg::experiments::ConfigurationResults> results = bsg::experiments::load_sweep_results(dir_.path(), false);
  ASSERT_EQ(results.size(), 2u);
  EXPECT_EQ(results[0].config_name, "lam_c=0.9");
  EXPECT_EQ(results[0].alg, bsg::Algorithm::cpo);
  EXPECT_EQ(results[0].seeds_expected, 1u);
  ASSERT_EQ(results[0].seeds.size(), 1u);
  EXPECT_EQ(results[0].seeds[0].seed, 1);
  EXPECT_DOUBLE_EQ(results[0].cost_limit, 25.0);
  EXPECT_EQ(results[1].config_name, "target_kl=0.01");
}

TEST_F(HandMadeSweep, MalformedEvaluationIsAnErrorNamingTheFile) {
  finish("SafetyBallCircle-v0/trpo/target_kl=0.01/seed=0", {100}, 10);
  const fs::path evaluation = dir_.path() / "SafetyBallCircle-v0/trpo/target_kl=0.01/seed=0/evaluation.json";
  std::ofstream(evaluation) << "{\"mean_return\": 1.0, \"episodes\": 2}";
  const auto result = run_bsg("table " + dir_.path().string());
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_NE(result.output.find(evaluation.string() + ": missing \"mean_cost\""), std::string::npos) << result.output;
}

// A sweep of TRPO-L with the PID multiplier (configs/grids/pid.yaml's shape)
// as `bsg sweep` leaves it: the grid copy, the manifest, some runs.
TEST(Table, PidRunsFormTheirOwnColumnEvenBeforeAnyHasStarted) {
  const TemporaryDirectory sweep;
  const std::string grid =
      "envs: [SafetyBallCircle-v0]\nseeds: [0]\nalgorithms:\n"
      "  lag-trpo: {fixed: {lambda_optimizer: PID}, axes: {pid_kp: [0.1, 0.5]}}\n";
  const std::vector<bsg::experiments::GridRun> runs = bsg::experiments::expand_grid(bsg::experiments::parse_grid(grid, "pid grid"));
  bsg::experiments::write_sweep_manifest(sweep.path(), runs);
  bsg::testing::write_text_file(sweep.path() / bsg::experiments::kSweepGridCopyName, grid);

  auto result = run_bsg("table " + sweep.path().string());  // nothing has run yet
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("| Env | TRPO-PID |\n|---|---|\n| BallCircle | missing |"), std::string::npos)
      << result.output;

  finish_run(sweep.path(), runs, "SafetyBallCircle-v0/lag-trpo/pid_kp=0.5/seed=0", {80}, 20);
  result = run_bsg("table " + sweep.path().string());
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("| BallCircle | **J=80.0 (0.80)** |"), std::string::npos) << result.output;
  EXPECT_NE(read_text_file(sweep.path() / "table1.csv").find(",TRPO-PID\n"), std::string::npos);
}

// `bsg table sweeps/report sweeps/pid --output DIR`: one table of both, each
// cell naming its configuration's directory under its own sweep.
TEST(Table, SeveralSweepsMakeOneTableWrittenToOutput) {
  const TemporaryDirectory root;
  const fs::path report = root.path() / "report";
  const fs::path pid = root.path() / "pid";
  const std::vector<bsg::experiments::GridRun> report_runs = bsg::experiments::expand_grid(bsg::experiments::parse_grid(
      "envs: [SafetyBallCircle-v0]\nseeds: [0]\nalgorithms:\n  trpo:\n  lag-trpo:\n", "report grid"));
  const std::vector<bsg::experiments::GridRun> pid_runs = bsg::experiments::expand_grid(bsg::experiments::parse_grid(
      "envs: [SafetyBallCircle-v0]\nseeds: [0]\nalgorithms:\n  lag-trpo: {fixed: {lambda_optimizer: PID}}\n",
      "pid grid"));
  fs::create_directories(report);
  fs::create_directories(pid);
  bsg::experiments::write_sweep_manifest(report, report_runs);
  bsg::experiments::write_sweep_manifest(pid, pid_runs);
  finish_run(report, report_runs, "SafetyBallCircle-v0/trpo/default/seed=0", {100}, 50);
  finish_run(report, report_runs, "SafetyBallCircle-v0/lag-trpo/default/seed=0", {60}, 30);
  finish_run(pid, pid_runs, "SafetyBallCircle-v0/lag-trpo/default/seed=0", {70}, 24);

  const auto refused = run_bsg("table " + report.string() + " " + pid.string());
  EXPECT_NE(refused.exit_code, 0);
  EXPECT_NE(refused.output.find("needs --output"), std::string::npos) << refused.output;

  const fs::path out = root.path() / "both";
  const auto result = run_bsg("table " + report.string() + " " + pid.string() + " --output " + out.string());
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("| Env | TRPO | TRPO-L | TRPO-PID |"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("| BallCircle | 1.00 (2.00) | 0.60 (1.20)\u2020 | **0.70 (0.96)** |"),
            std::string::npos)
      << result.output;
  const std::string csv = read_text_file(out / "table1.csv");
  EXPECT_NE(csv.find("," + (pid / "SafetyBallCircle-v0/lag-trpo/default").generic_string() + ","), std::string::npos)
      << csv;
  EXPECT_FALSE(fs::exists(report / "table1.md"));  // neither sweep's own table is overwritten
}

// Table 1 both ways: a faithful sweep and the same grid with `learner: corrected`
// (configs/grids/report_corrected.yaml's shape). The corrected runs form
// columns of their own, read from their config.yaml (or, before any has
// started, from the grid copy), with J over the faithful TRPO's.
TEST(Table, CorrectedLearnerSweepsGiveColumnsBesideTheFaithfulOnes) {
  const TemporaryDirectory root;
  const fs::path faithful = root.path() / "faithful";
  const fs::path corrected = root.path() / "corrected";
  const std::string algorithms = "envs: [SafetyBallRun-v0]\nseeds: [0]\nalgorithms:\n  trpo:\n  lag-trpo:\n";
  const std::string corrected_grid = algorithms + "fixed: {learner: corrected}\n";
  const std::vector<bsg::experiments::GridRun> faithful_runs = bsg::experiments::expand_grid(bsg::experiments::parse_grid(algorithms, "faithful grid"));
  const std::vector<bsg::experiments::GridRun> corrected_runs = bsg::experiments::expand_grid(bsg::experiments::parse_grid(corrected_grid, "corrected grid"));
  fs::create_directories(faithful);
  fs::create_directories(corrected);
  bsg::experiments::write_sweep_manifest(faithful, faithful_runs);
  bsg::experiments::write_sweep_manifest(corrected, corrected_runs);
  bsg::testing::write_text_file(corrected / bsg::experiments::kSweepGridCopyName, corrected_grid);
  finish_run(faithful, faithful_runs, "SafetyBallRun-v0/trpo/default/seed=0", {400}, 230);
  finish_run(faithful, faithful_runs, "SafetyBallRun-v0/lag-trpo/default/seed=0", {100}, 60);
  finish_run(corrected, corrected_runs, "SafetyBallRun-v0/trpo/default/seed=0", {2000}, 230);

  const fs::path out = root.path() / "both";
  const auto result = run_bsg("table " + faithful.string() + " " + corrected.string() + " --output " + out.string());
  ASSERT_EQ(result.exit_code, 0) << result.output;
  // TRPO-L corrected has not started: its column comes from the grid copy.
  EXPECT_NE(result.output.find("| Env | TRPO | TRPO-L | TRPO corrected | TRPO-L corrected |\n"), std::string::npos)
      << result.output;
  EXPECT_NE(result.output.find("| BallRun | 1.00 (9.20) | **0.25 (2.40)\u2020** | 5.00 (9.20) | missing |"),
            std::string::npos)
      << result.output;
  EXPECT_NE(read_text_file(out / "table1.csv").find(",TRPO corrected\n"), std::string::npos);
}

TEST(Table, AMissingSweepDirectoryIsNamed) {
  const auto result = run_bsg("table /nonexistent/sweep");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_NE(result.output.find("sweep directory /nonexistent/sweep does not exist"), std::string::npos)
      << result.output;
}

TEST(Table, AnUnknownScoreIsACommandLineError) {
  const auto result = run_bsg("table /tmp --score median");
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_NE(result.output.find("median"), std::string::npos) << result.output;
}

}  // namespace
