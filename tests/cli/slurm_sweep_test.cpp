// `bsg sweep --slurm` and `--status` from the command line, without a
// cluster: the dry run prints the job-array script and submits nothing, bad
// option values and a missing sbatch are named, and `--status` refuses a
// folder that is no sweep.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "../test_support.h"
#include "run_bsg.h"

namespace fs = std::filesystem;
using bsg::testing::run_bsg;

namespace {

using bsg::testing::kSource;
const std::string kQuick = (kSource / "configs" / "grids" / "quick.yaml").string();

using bsg::testing::contains;

}  // namespace

TEST(SlurmSweep, DryRunPrintsTheScriptWithEveryRunAndSubmitsNothing) {
  bsg::testing::TemporaryDirectory temp;
  const fs::path out = temp.path() / "quick";
  const auto result = run_bsg("sweep " + kQuick + " --slurm --dry-run --max-running 3 --partition short --time 1:00:00"
                              " --sbatch-arg=--account=abc --out " + out.string());
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_TRUE(contains(result.output, "#SBATCH --array=0-3%3")) << result.output;
  EXPECT_TRUE(contains(result.output, "#SBATCH --partition=short"));
  EXPECT_TRUE(contains(result.output, "#SBATCH --time=1:00:00"));
  EXPECT_TRUE(contains(result.output, "#SBATCH --account=abc"));
  EXPECT_TRUE(contains(result.output, "seed=1  # 3"));
  EXPECT_TRUE(contains(result.output, "4 runs: 0 finished, 0 queued, 0 running, 4 to submit"));
  EXPECT_FALSE(fs::exists(out)) << "a dry run wrote the sweep directory";
}

TEST(SlurmSweep, NoSbatchOnPathIsAnErrorNamingSlurmAndTheOption) {
  bsg::testing::TemporaryDirectory temp;
  // run_bsg cannot change PATH; call the program through env instead.
  const std::string command = "env PATH=" + temp.path().string() + " " + std::string(BSG_BINARY) + " sweep " + kQuick +
                              " --slurm --out " + (temp.path() / "q2").string() + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string output;
  char chunk[4096];
  std::size_t n = 0;
  while ((n = fread(chunk, 1, sizeof chunk, pipe)) > 0) output.append(chunk, n);
  const int status = pclose(pipe);
  EXPECT_NE(WEXITSTATUS(status), 0);
  EXPECT_TRUE(contains(output, "--slurm")) << output;
  EXPECT_TRUE(contains(output, "Slurm command 'sbatch' is not on PATH")) << output;
}

TEST(SlurmSweep, BadOptionValuesAreNamed) {
  const auto zero = run_bsg("sweep " + kQuick + " --slurm --max-running 0 --dry-run");
  EXPECT_NE(zero.exit_code, 0);
  EXPECT_TRUE(contains(zero.output, "--max-running")) << zero.output;
  const auto without_slurm = run_bsg("sweep " + kQuick + " --partition short --dry-run");
  EXPECT_NE(without_slurm.exit_code, 0);
  EXPECT_TRUE(contains(without_slurm.output, "--partition")) << without_slurm.output;
  EXPECT_TRUE(contains(without_slurm.output, "--slurm")) << without_slurm.output;
}

TEST(SlurmSweep, StatusOfAFolderThatIsNoSweepIsAnError) {
  bsg::testing::TemporaryDirectory temp;
  const auto result = run_bsg("sweep --status " + temp.path().string());
  EXPECT_NE(result.exit_code, 0);
  EXPECT_TRUE(contains(result.output, "is not a sweep directory")) << result.output;
}
