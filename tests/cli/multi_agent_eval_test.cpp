// `bsg eval` of a multi-agent run (docs/multi_agent.md#learners) end to end: a tiny MAPPO-L run is
// trained, then `bsg eval` with the trainer's seed and episode count reproduces its
// evaluation.json, returns.csv and costs.csv; sampled actions are refused in one line (the
// recording: tests/render/eval_recording_test.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "../test_support.h"
#include "run_bsg.h"

namespace fs = std::filesystem;

namespace {
namespace multi_agent_eval_test {

using bsg::testing::kConfigsOption;
using bsg::testing::read_text_file;
using bsg::testing::run_bsg;
using bsg::testing::TemporaryDirectory;

// Two Balls on Circle, 2 epochs of 400 team steps, an 8-unit actor and critics; 4 evaluation
// episodes of 200 steps. Seed 2: agent_1 leaves the circle in the evaluation (a non-zero cost).
std::string train_tiny_run(const TemporaryDirectory& dir) {
  return "train --set env_id=SafetyBallCircle2-v0 --set alg=mappo-lag --set seed=2 --set epochs=2 "
         "--set steps_per_epoch=400 --set max_ep_len=200 --set hidden_sizes=[8] --set eval_episodes=4 "
         "--set policy_minibatch_size=400" +
         kConfigsOption + " --quiet --out " + dir.str("run");
}

nlohmann::json json_in(const std::string& text) { return nlohmann::json::parse(text.substr(text.find('{'))); }

std::vector<double> numbers_per_line(const std::string& text) {
  std::vector<double> values;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) values.push_back(std::stod(line));
  return values;
}

}  // namespace multi_agent_eval_test
}  // namespace

// The training's final evaluation ran inside the trainer's process on the family it had trained;
// `bsg eval` is a fresh process that rebuilds the family from config.yaml, loads every agent slot
// from checkpoint.bin and re-makes the environment. Both act through the family's one evaluation
// loop, so this checks the path from the run directory to that loop (checkpoint, config, seed and
// episode count, the printed and JSON output), not the loop itself: equal numbers mean the loaded
// agents act as the trained ones did.
TEST(MultiAgentEval, ReproducesTheTrainingsFinalEvaluation) {
  using namespace multi_agent_eval_test;
  TemporaryDirectory dir;
  const auto trained = run_bsg(train_tiny_run(dir));
  ASSERT_EQ(trained.exit_code, 0) << trained.output;
  const fs::path run = dir.path() / "run";
  const nlohmann::json written = json_in(read_text_file(run / "evaluation.json"));

  const auto evaluated = run_bsg("eval " + run.string() + " --json");  // the config's seed and eval_episodes
  ASSERT_EQ(evaluated.exit_code, 0) << evaluated.output;
  const nlohmann::json again = json_in(evaluated.output);
  for (const char* key : {"mean_return", "mean_cost", "episodes", "mean_length", "agents"}) {
    EXPECT_EQ(again.at(key), written.at(key)) << key;
  }
  EXPECT_EQ(again.at("returns").get<std::vector<double>>(), numbers_per_line(read_text_file(run / "returns.csv")));
  EXPECT_EQ(again.at("costs").get<std::vector<double>>(), numbers_per_line(read_text_file(run / "costs.csv")));
  EXPECT_EQ(again.at("episodes"), 4);
  EXPECT_GT(again.at("mean_cost").get<double>(), 0.0);  // the cost is checked on something

  // The team's J and H are the agents' mean (hand computation from the agents' own).
  const nlohmann::json& agents = again.at("agents");
  ASSERT_EQ(agents.size(), 2u);
  EXPECT_EQ(agents[0].at("agent"), "agent_0");
  EXPECT_EQ(agents[1].at("agent"), "agent_1");
  const double team_return = (agents[0].at("mean_return").get<double>() + agents[1].at("mean_return").get<double>()) / 2;
  const double team_cost = (agents[0].at("mean_cost").get<double>() + agents[1].at("mean_cost").get<double>()) / 2;
  EXPECT_NEAR(again.at("mean_return").get<double>(), team_return, 1e-12 * std::abs(team_return));
  EXPECT_NEAR(again.at("mean_cost").get<double>(), team_cost, 1e-12 * team_cost);

  // The text output: the single-agent lines, each agent's below J and H.
  const auto plain = run_bsg("eval " + run.string() + " --actions mean");
  ASSERT_EQ(plain.exit_code, 0) << plain.output;
  const std::string agent_1 = "agent_1 J (mean return) " + agents[1].at("mean_return").dump() + " H (mean cost) " +
                              agents[1].at("mean_cost").dump() + "\n";
  for (const std::string& line :
       {std::string("episodes 4\n"), "J (mean return) " + written.at("mean_return").dump() + "\n",
        "H (mean cost) " + written.at("mean_cost").dump() + "\n", agent_1, std::string("actions mean (deterministic)\n")}) {
    EXPECT_NE(plain.output.find(line), std::string::npos) << line << " in\n" << plain.output;
  }
}

TEST(MultiAgentEval, SampledActionsAreRefusedInOneLineBeforeARecordingStarts) {
  using namespace multi_agent_eval_test;
  TemporaryDirectory dir;
  ASSERT_EQ(run_bsg(train_tiny_run(dir)).exit_code, 0);
  const fs::path video = dir.path() / "episodes.mp4";
  const auto refused = run_bsg("eval " + dir.str("run") + " --actions sampled --video " + video.string());
  EXPECT_NE(refused.exit_code, 0);
  EXPECT_NE(refused.output.find("a multi-agent run (alg mappo-lag) evaluates its agents' mean actions; sampled actions "
                                "do not apply"),
            std::string::npos)
      << refused.output;
  EXPECT_EQ(std::count(refused.output.begin(), refused.output.end(), '\n'), 1) << refused.output;
  EXPECT_FALSE(fs::exists(video));  // refused before the recording opens its file
}
