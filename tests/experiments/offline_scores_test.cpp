// The offline table in DSRL's format from hand-made run directories: the last
// evaluated epoch's normalised reward and cost per seed, their mean, the
// bootstrap interval of two seeds (every resample's mean lies between the two
// values, and with 2000 resamples both extremes are drawn), safety at a mean
// normalised cost of 1, and the online learners left out.
#include "experiments/offline_scores.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "../test_support.h"

namespace bsg::experiments {
namespace {

namespace fs = std::filesystem;
using bsg::testing::TemporaryDirectory;
using bsg::testing::write_text_file;

// A progress.csv whose evaluated epochs are 1 and 3 (2 is not evaluated: nan).
fs::path offline_run(const fs::path& dir, double last_reward, double last_cost) {
  fs::create_directories(dir);
  write_text_file(dir / "progress.csv",
                  "epoch,updates,loss,eval_return,eval_cost,eval_length,normalized_reward,normalized_cost,time_update_s,"
                  "time_s\n"
                  "0,10,1,5,2,250,0.9,0.1,1,1\n"
                  "1,20,1,nan,nan,nan,nan,nan,1,2\n"
                  "2,30,1,5,2,250," + std::to_string(last_reward) + "," + std::to_string(last_cost) + ",1,3\n");
  return dir;
}

ConfigurationResults offline_config(const std::string& env, Algorithm alg, std::vector<fs::path> runs) {
  ConfigurationResults config;
  config.env_id = env;
  config.alg = alg;
  config.config_name = "default";
  config.cost_limit = 25.0;
  config.seeds_expected = runs.size();
  for (std::size_t i = 0; i < runs.size(); ++i) {
    SeedResult seed;
    seed.seed = static_cast<std::int64_t>(i);
    seed.run_dir = runs[i];
    config.seeds.push_back(seed);
  }
  return config;
}

TEST(OfflineScores, MeansOfTheLastEvaluationWithTheTwoSeedIntervalBetweenThem) {
  TemporaryDirectory directory("offline_scores");
  const fs::path root = directory.path();
  const std::vector<ConfigurationResults> results = {
      offline_config("SafetyBallCircle-v0", Algorithm::bc_all,
                     {offline_run(root / "a0", 0.5, 1.5), offline_run(root / "a1", 0.7, 2.5)}),
      offline_config("SafetyBallCircle-v0", Algorithm::bc_safe,
                     {offline_run(root / "s0", 0.25, 0.5), offline_run(root / "s1", 0.375, 0.75)}),
      offline_config("SafetyBallCircle-v0", Algorithm::trpo, {root / "not-read"}),  // online: left out
      offline_config("SafetyBallRun-v0", Algorithm::coptidice, {offline_run(root / "c0", 0.125, 1.0)}),
  };
  const OfflineScores scores = build_offline_scores(results, {});
  ASSERT_EQ(scores.rows.size(), 3u);
  const OfflineScoreRow& all = scores.rows[0];
  EXPECT_EQ(all.column, "BC-All");
  EXPECT_EQ(all.seeds, 2u);
  EXPECT_NEAR(all.normalized_reward.point, 0.6, 1e-12);
  EXPECT_NEAR(all.normalized_cost.point, 2.0, 1e-12);
  // Resampled means of two values lie in [min, max]; both ends come up (each with chance 1/4 per draw).
  EXPECT_NEAR(all.normalized_reward.low, 0.5, 1e-12);
  EXPECT_NEAR(all.normalized_reward.high, 0.7, 1e-12);
  EXPECT_NEAR(all.normalized_cost.low, 1.5, 1e-12);
  EXPECT_NEAR(all.normalized_cost.high, 2.5, 1e-12);
  EXPECT_FALSE(all.safe());
  const OfflineScoreRow& safe = scores.rows[1];
  EXPECT_NEAR(safe.normalized_reward.point, 0.3125, 1e-12);
  EXPECT_NEAR(safe.normalized_cost.point, 0.625, 1e-12);
  EXPECT_TRUE(safe.safe());
  // One seed: its value, no interval, and a note; a mean cost of exactly 1 is safe.
  const OfflineScoreRow& one = scores.rows[2];
  EXPECT_NEAR(one.normalized_reward.point, 0.125, 1e-12);
  EXPECT_TRUE(std::isnan(one.normalized_reward.low));
  EXPECT_TRUE(one.safe());
  ASSERT_EQ(scores.notes.size(), 1u);
  EXPECT_NE(scores.notes[0].find("SafetyBallRun-v0/coptidice/default: one finished seed"), std::string::npos);

  const std::string markdown = offline_scores_markdown(scores);
  // BC-Safe is the only safe learner on Circle, so its reward is bold; BC-All's cells carry the dagger.
  EXPECT_NE(markdown.find("| SafetyBallCircle-v0 | 25.0 | 0.60 [0.50, 0.70] † | 2.00 [1.50, 2.50] † | "
                          "**0.31 [0.25, 0.38]** | 0.62 [0.50, 0.75] | missing | missing |"),
            std::string::npos)
      << markdown;
  EXPECT_NE(markdown.find("| SafetyBallRun-v0 | 25.0 | missing | missing | missing | missing | **0.12** | 1.00 |"),
            std::string::npos)
      << markdown;
  const std::string csv = offline_scores_csv(scores);
  EXPECT_NE(csv.find("SafetyBallCircle-v0,BC-Safe,default,25.0,2,0.3125,0.25,0.375,0.625,0.5,0.75,1,0.95\n"),
            std::string::npos)
      << csv;
}

TEST(OfflineScores, AProgressLogWithoutTheNormalisedColumnsIsNamed) {
  TemporaryDirectory directory("offline_scores");
  fs::create_directories(directory.path() / "r");
  write_text_file(directory.path() / "r" / "progress.csv", "epoch,eval_return\n0,1\n");
  const std::vector<ConfigurationResults> results = {
      offline_config("SafetyBallCircle-v0", Algorithm::cpq, {directory.path() / "r"})};
  try {
    build_offline_scores(results, {});
    FAIL() << "a progress.csv without normalized_reward was read";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find((directory.path() / "r" / "progress.csv").string() +
                                             ": no column normalized_reward"),
              std::string::npos)
        << error.what();
  }
}

}  // namespace
}  // namespace bsg::experiments
