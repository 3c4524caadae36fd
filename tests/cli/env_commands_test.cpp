// `bsg envs`, `bsg rollout` and `bsg bench` end to end: output content, JSON
// that parses, errors for unknown ids (listing the valid ones) and bad counts;
// the multi-agent ids listed against their registry and docs/multi_agent.md's table.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "envs/env.h"
#include "envs/multi_agent_env.h"
#include "run_bsg.h"

namespace {

using bsg::testing::run_bsg;

// stdout and stderr are captured together; the JSON starts at the first bracket.
nlohmann::json parse_json(const std::string& output) {
  const size_t start = output.find_first_of("[{");
  if (start == std::string::npos) throw std::runtime_error("no JSON in: " + output);
  return nlohmann::json::parse(output.substr(start));
}

TEST(EnvsCommand, ListsEveryRegisteredIdWithItsSizes) {
  const auto result = run_bsg("envs");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  for (const std::string& id : bsg::envs::registered_ids()) {
    EXPECT_NE(result.output.find(id), std::string::npos) << id;
  }
  EXPECT_NE(result.output.find("SafetyBallReach-v0            57       2       250          10"),
            std::string::npos)
      << result.output;
}

TEST(EnvsCommand, JsonParsesAndMatchesTheSpecTable) {
  const auto result = run_bsg("envs --json");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const nlohmann::json list = parse_json(result.output);
  ASSERT_EQ(list.size(), bsg::envs::registered_ids().size());
  bool found = false;
  for (const auto& entry : list) {
    if (entry.at("id") == "SafetyBallGather-v0") {
      found = true;
      EXPECT_EQ(entry.at("observation_dim"), 39);
      EXPECT_EQ(entry.at("action_dim"), 2);
      EXPECT_EQ(entry.at("max_episode_steps"), 250);
      EXPECT_EQ(entry.at("cost_limit"), 0.2);
    }
  }
  EXPECT_TRUE(found);
}

// The whitespace-separated words of the first line of `output` that starts
// with `id` followed by a space; empty if there is none.
std::vector<std::string> row_of(const std::string& output, const std::string& id) {
  std::istringstream lines(output);
  for (std::string line; std::getline(lines, line);) {
    if (!line.starts_with(id + " ")) continue;
    std::istringstream words(line);
    std::vector<std::string> row;
    for (std::string word; words >> word;) row.push_back(word);
    return row;
  }
  return {};
}

TEST(EnvsCommand, ListsTheMultiAgentIdsInASectionOfTheirOwn) {
  const auto result = run_bsg("envs");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const size_t section = result.output.find("\nmulti-agent");
  ASSERT_NE(section, std::string::npos) << result.output;
  for (const std::string& id : bsg::envs::registered_ids()) {
    EXPECT_LT(result.output.find(id + " "), section) << id;  // single-agent ids above it
  }
  const std::vector<std::string> ids = bsg::envs::multi_agent_ids();
  ASSERT_EQ(ids.size(), 9u);  // docs/multi_agent.md#ids
  for (const std::string& id : ids) {
    const size_t at = result.output.find(id + " ");
    EXPECT_NE(at, std::string::npos) << id;
    EXPECT_GT(at, section) << id;
  }
  // Rows of docs/multi_agent.md#ids: agents, observation and action per agent, state, steps, d.
  EXPECT_EQ(row_of(result.output, "SafetyBallCircle3-v0"),
            (std::vector<std::string>{"SafetyBallCircle3-v0", "3", "12,12,12", "2,2,2", "24", "250", "25"}));
  EXPECT_EQ(row_of(result.output, "SafetyCarCircle2-v0"),
            (std::vector<std::string>{"SafetyCarCircle2-v0", "2", "10,10", "2,2", "16", "500", "25"}));
  EXPECT_EQ(row_of(result.output, "SafetyAntRun4x2-v0"),
            (std::vector<std::string>{"SafetyAntRun4x2-v0", "4", "18,18,18,18", "2,2,2,2", "33", "1000", "25"}));
  EXPECT_EQ(row_of(result.output, "SafetyAntCircle2x4-v0"),
            (std::vector<std::string>{"SafetyAntCircle2x4-v0", "2", "24,24", "4,4", "34", "1000", "25"}));
}

TEST(EnvsCommand, MultiAgentJsonIsItsOwnArrayAndTheSingleAgentOneStaysAsItWas) {
  const nlohmann::json single = parse_json(run_bsg("envs --json").output);
  for (const auto& entry : single) EXPECT_FALSE(entry.contains("agents")) << entry.at("id");
  const auto result = run_bsg("envs --multi-agent --json");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const nlohmann::json list = parse_json(result.output);
  std::vector<std::string> listed;
  for (const auto& entry : list) listed.push_back(entry.at("id"));
  EXPECT_EQ(listed, bsg::envs::multi_agent_ids());
  for (const auto& entry : list) {
    if (entry.at("id") != "SafetyAntRun2x4-v0") continue;
    EXPECT_EQ(entry.at("agents"), 2);  // MaMuJoCo's 2x4: front and back legs
    EXPECT_EQ(entry.at("observation_dims"), nlohmann::json({23, 23}));  // 13 + 8 + 2
    EXPECT_EQ(entry.at("action_dims"), nlohmann::json({4, 4}));
    EXPECT_EQ(entry.at("state_dim"), 33);  // the Ant's single-agent observation (report Table 3)
    EXPECT_EQ(entry.at("team_reward"), true);
    EXPECT_EQ(entry.at("team_cost"), true);
  }
  const auto table = run_bsg("envs --multi-agent");
  ASSERT_EQ(table.exit_code, 0) << table.output;
  EXPECT_EQ(table.output.find("SafetyBallReach-v0"), std::string::npos) << table.output;
  EXPECT_NE(table.output.find("SafetyBallCircle2-v0"), std::string::npos) << table.output;
}

TEST(EnvsCommand, DescribesAMultiAgentIdWithItsOverrides) {
  const auto result = run_bsg("envs --describe SafetyBallCircle2-v0 --set bodies=3 --set circle_radius=6");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  // Three Balls: 7 + 1 + 2*(3-1) = 12 entries each, 8 per robot in the state (docs/multi_agent.md).
  EXPECT_NE(result.output.find("# SafetyBallCircle2-v0: 3 agents, observation 12,12,12, action 2,2,2, state 24"),
            std::string::npos)
      << result.output;
  EXPECT_NE(result.output.find("\nbodies: 3  #"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("\npartition: body  #"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("\nagent: Ball  #"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("\ncircle_radius: 6.0  #"), std::string::npos) << result.output;
  EXPECT_EQ(result.output.find("\nname:"), result.output.rfind("\nname:"));  // one name line
  const auto bad = run_bsg("envs --describe SafetyAntRun2x4-v0 --set partition=3x3");
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.output.find("partition=3x3"), std::string::npos) << bad.output;
}

TEST(RolloutCommand, PrintsEpisodesAndSummary) {
  const auto result = run_bsg("rollout --env SafetyBallCircle-v0 --policy zero --episodes 2 --seed 3");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("mean return"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("mean cost"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("mean length 250.000"), std::string::npos) << result.output;
}

TEST(RolloutCommand, JsonIsReproducibleAcrossProcesses) {
  const std::string command = "rollout --env SafetyBallReach-v0 --episodes 2 --seed 9 --json";
  const auto first = run_bsg(command);
  const auto second = run_bsg(command);
  ASSERT_EQ(first.exit_code, 0) << first.output;
  EXPECT_EQ(first.output, second.output);  // same seed, new process: bit-identical
  const nlohmann::json out = parse_json(first.output);
  ASSERT_EQ(out.at("episodes").size(), 2u);
  EXPECT_EQ(out.at("episodes")[0].at("length"), 250);
  // Zero policy on the Ball: no motion, zero return and cost (docs/environments.md#ball).
  const nlohmann::json zero =
      parse_json(run_bsg("rollout --env SafetyBallRun-v0 --policy zero --json").output);
  EXPECT_NEAR(zero.at("mean").at("return").get<double>(), 0.0, 1e-9);
  EXPECT_EQ(zero.at("mean").at("cost").get<double>(), 0.0);
}

TEST(RolloutCommand, UnknownEnvIsAnErrorListingTheValidIds) {
  const auto result = run_bsg("rollout --env SafetyBallDance-v0");
  EXPECT_NE(result.exit_code, 0);
  EXPECT_NE(result.output.find("SafetyBallDance-v0"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("SafetyBallCircle-v0"), std::string::npos) << result.output;
}

TEST(RolloutCommand, BadEpisodeCountOrPolicyIsACommandLineError) {
  EXPECT_EQ(run_bsg("rollout --env SafetyBallRun-v0 --episodes 0").exit_code, 2);
  EXPECT_EQ(run_bsg("rollout --env SafetyBallRun-v0 --episodes many").exit_code, 2);
  EXPECT_EQ(run_bsg("rollout --env SafetyBallRun-v0 --policy greedy").exit_code, 2);
  EXPECT_EQ(run_bsg("rollout --episodes 2").exit_code, 2);  // --env is required
}

TEST(BenchCommand, PrintsEnvAndPhysicsRates) {
  const auto result = run_bsg("bench --env SafetyBallRun-v0 --steps 300");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("env steps/s"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("physics steps/s"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("SafetyBallRun-v0"), std::string::npos) << result.output;
  const nlohmann::json list = parse_json(run_bsg("bench --env SafetyBallRun-v0 --steps 300 --json").output);
  ASSERT_EQ(list.size(), 1u);
  EXPECT_GT(list[0].at("env_steps_per_second").get<double>(), 0);
  EXPECT_GT(list[0].at("physics_steps_per_second").get<double>(), 0);
}

TEST(BenchCommand, UnknownEnvAndBadStepsAreErrors) {
  const auto unknown = run_bsg("bench --env Nope-v0 --steps 10");
  EXPECT_NE(unknown.exit_code, 0);
  EXPECT_NE(unknown.output.find("SafetyBallRun-v0"), std::string::npos) << unknown.output;
  EXPECT_EQ(run_bsg("bench --steps 0").exit_code, 2);
}

TEST(BenchCommand, TrainTimesEveryEpochAndPrintsTheMedians) {
  const nlohmann::json result = parse_json(run_bsg(
      "bench --train --env SafetyBallCircle-v0 --alg trpo --epochs 2 --set steps_per_epoch=1000 --set dtype=float64 "
      "--json").output);
  EXPECT_EQ(result.at("alg"), "trpo");
  EXPECT_EQ(result.at("dtype"), "float64");
  EXPECT_EQ(result.at("steps_per_epoch"), 1000);
  ASSERT_EQ(result.at("epochs").size(), 2u);
  for (const nlohmann::json& epoch : result.at("epochs")) {
    const double collect = epoch.at("collect_s"), policy = epoch.at("policy_update_s"),
                 value = epoch.at("value_fit_s"), update = epoch.at("update_s"), total = epoch.at("total_s");
    EXPECT_GT(collect, 0);
    EXPECT_GT(policy, 0);
    EXPECT_GT(value, 0);
    EXPECT_GE(update, policy + value);  // the update also holds the normalisers and checks
    EXPECT_GE(total, collect + update);
  }
  EXPECT_GT(result.at("median").at("total_s").get<double>(), 0);
  const auto table = run_bsg("bench --train --env SafetyBallCircle-v0 --alg trpo --epochs 1 --set steps_per_epoch=1000");
  ASSERT_EQ(table.exit_code, 0) << table.output;
  EXPECT_NE(table.output.find("median"), std::string::npos) << table.output;
  EXPECT_NE(table.output.find("dtype float32"), std::string::npos) << table.output;  // the shipped default
}

TEST(BenchCommand, TrainOptionsAreCheckedAndConfigErrorsNameTheKey) {
  EXPECT_EQ(run_bsg("bench --train --steps 100").exit_code, 2);  // --steps times env steps only
  EXPECT_EQ(run_bsg("bench --alg trpo").exit_code, 2);           // --alg needs --train
  const auto bad = run_bsg("bench --train --env SafetyBallCircle-v0 --epochs 1 --set dtype=float16");
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.output.find("dtype"), std::string::npos) << bad.output;
}

}  // namespace
