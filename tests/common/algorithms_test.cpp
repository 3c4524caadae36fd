// The table of algorithms (common/algorithms.h) against what the shipped
// algorithm files say of each algorithm: a first-order algorithm's file sets
// actor_lr, one with a Lagrange multiplier sets lambda_lr, one with PPO's
// clipped ratio sets clip, an off-policy one sets actor_lr and its critics' critic_lr. The files are written for the updates in algos/,
// so they are a second, independent statement of each algorithm's family.
#include "common/algorithms.h"

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <set>
#include <string>

namespace bsg {
namespace {

const std::filesystem::path kAlgorithmFiles = std::filesystem::path(BSG_SOURCE_DIR) / "configs" / "algorithms";

TEST(Algorithms, EveryAlgorithmHasItsFileAndEveryFileItsAlgorithm) {
  std::set<std::string> files;
  for (const auto& entry : std::filesystem::directory_iterator(kAlgorithmFiles)) {
    if (entry.path().extension() == ".yaml") files.insert(entry.path().stem().string());
  }
  std::set<std::string> names;
  for (const AlgorithmInfo& info : kAlgorithms) names.insert(std::string(info.name));
  EXPECT_EQ(files, names);
}

TEST(Algorithms, FamiliesAgreeWithTheShippedAlgorithmFiles) {
  for (const AlgorithmInfo& info : kAlgorithms) {
    SCOPED_TRACE(std::string(info.name));
    const YAML::Node file = YAML::LoadFile((kAlgorithmFiles / (std::string(info.name) + ".yaml")).string());
    EXPECT_EQ(info.family == AlgorithmFamily::first_order || info.family == AlgorithmFamily::off_policy ||
                  info.family == AlgorithmFamily::offline ||
                  (info.family == AlgorithmFamily::multi_agent && info.alg != Algorithm::macpo),  // MACPO: CPO's step
              static_cast<bool>(file["actor_lr"]));
    EXPECT_EQ(info.family == AlgorithmFamily::offline, static_cast<bool>(file["updates_per_epoch"]));
    // Critics: the off-policy learners, CPQ, BCQ-Lag and COptiDICE (its nu and chi networks).
    EXPECT_EQ(info.family == AlgorithmFamily::off_policy || info.alg == Algorithm::cpq || info.alg == Algorithm::bcq_lag ||
                  info.alg == Algorithm::coptidice,
              static_cast<bool>(file["critic_lr"]));
    EXPECT_EQ(info.lagrange_multiplier, static_cast<bool>(file["lambda_lr"]));
    EXPECT_EQ(info.clipped_surrogate, static_cast<bool>(file["clip"]));
  }
}

TEST(Algorithms, OnlyTheUnconstrainedIgnoreTheCostAndOnlyMultipliersHaveAPidLabel) {
  for (const AlgorithmInfo& info : kAlgorithms) {
    SCOPED_TRACE(std::string(info.name));
    // TRPO and PPO are the report's unconstrained baselines; SAC, TD3 and DDPG the off-policy ones;
    // BC-All the offline one (BC-Safe is constrained by its choice of episodes); MAPPO and HAPPO the
    // multi-agent ones.
    EXPECT_EQ(ignores_cost(info.alg), info.name == "trpo" || info.name == "ppo" || info.name == "sac" ||
                                          info.name == "td3" || info.name == "ddpg" || info.name == "bc-all" ||
                                          info.name == "mappo" || info.name == "happo");
    EXPECT_EQ(info.pid_label.empty(), !info.lagrange_multiplier);
  }
  std::set<std::string_view> labels;
  for (const AlgorithmInfo& info : kAlgorithms) {
    EXPECT_TRUE(labels.insert(info.label).second) << info.label;
    if (!info.pid_label.empty()) {
      EXPECT_TRUE(labels.insert(info.pid_label).second) << info.pid_label;
    }
  }
}

}  // namespace
}  // namespace bsg
