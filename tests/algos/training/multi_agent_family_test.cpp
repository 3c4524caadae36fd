// The multi-agent family (algos/training/multi_agent_family.h, algos/multi_agent/): the agent id's
// one-hot layout against hand-written inputs, MAPPO-L's multiplier on a hand-made cost sequence,
// a run stopped after one epoch and resumed writing the uninterrupted run's files, the shared
// policy's run, HAPPO's and MACPO's runs resumed likewise, and the bad pairings of env_id and alg
// (and happo with share_policy) refused in one line.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "../../test_support.h"
#include "algos/lagrange/constraint_multipliers.h"
#include "algos/multi_agent/agent_id_input.h"
#include "algos/multi_agent/multi_agent_networks.h"
#include "algos/training/multi_agent_family.h"
#include "algos/training/multi_agent_trainer.h"
#include "algos/training/run_start.h"
#include "common/config_error.h"
#include "common/run_config_resolve.h"

namespace fs = std::filesystem;

namespace bsg::algos {
namespace {
namespace multi_agent_family_test {

RunConfig ma_config(const std::string& alg, std::vector<std::string> more = {}) {
  RunConfigRequest request;
  request.configs_dir = fs::path(BSG_SOURCE_DIR) / "configs";
  request.set_arguments = {"env_id=SafetyBallCircle2-v0", "alg=" + alg, "epochs=3", "steps_per_epoch=200",
                           "max_ep_len=100", "hidden_sizes=[8]", "eval_episodes=2", "save_freq=1", "train_v_iterations=2"};
  if (alg != "macpo") {  // MACPO's actors take CPO's step, without PPO's keys
    request.set_arguments.insert(request.set_arguments.end(), {"policy_minibatch_size=100", "update_iters=2"});
  }
  request.set_arguments.insert(request.set_arguments.end(), more.begin(), more.end());
  return resolve_training_config(request);
}

std::string without_times(const fs::path& path) {
  std::string text;
  const auto rows = bsg::testing::read_csv_rows(path);
  for (const auto& row : rows) {
    for (std::size_t c = 0; c < row.size(); ++c) {
      const std::string& name = rows.front()[c];
      if (name.rfind("time_", 0) != 0) text += row[c] + ",";
    }
    text += "\n";
  }
  return text;
}

TEST(MultiAgentFamily, AgentIdIsAOneHotAfterTheInput) {
  const Eigen::Vector2d x(0.5, -2.0);
  Eigen::VectorXd input(5);
  write_agent_input(x, 1, 3, input);
  EXPECT_EQ(input, (Eigen::VectorXd(5) << 0.5, -2.0, 0.0, 1.0, 0.0).finished());
  Eigen::VectorXd plain(2);
  write_agent_input(x, 7, agent_id_width(false, 3), plain);  // no id without sharing
  EXPECT_EQ(plain, Eigen::VectorXd(x));
  EXPECT_THROW(write_agent_input(x, 3, 3, input), std::invalid_argument);
  Eigen::MatrixXd rows(2, 4);
  write_agent_inputs(Eigen::Matrix2d::Identity(), 0, 2, rows);
  EXPECT_EQ(rows, (Eigen::MatrixXd(2, 4) << 1, 0, 1, 0, 0, 1, 1, 0).finished());
}

TEST(MultiAgentFamily, SharedNetworksSeeTheirAgentsIdOnUnnormalisedObservations) {
  const RunConfig config = ma_config("mappo", {"share_policy=true", "use_standardized_obs=false"});
  Rng rng(1);
  const MultiAgentNetworks networks(MultiAgentSizes{{3, 3}, {2, 2}, 4}, config, false, rng);
  EXPECT_EQ(networks.slot_count(), 1);
  Eigen::VectorXd input(5);
  networks.policy_input(1, Eigen::Vector3d(1, 2, 3), input);
  EXPECT_EQ(input, (Eigen::VectorXd(5) << 1, 2, 3, 0, 1).finished());
  Eigen::VectorXd critic(6);
  networks.critic_input(0, Eigen::Vector4d(4, 3, 2, 1), critic);
  EXPECT_EQ(critic, (Eigen::VectorXd(6) << 4, 3, 2, 1, 1, 0).finished());
  // Unequal observation sizes cannot share.
  EXPECT_THROW(MultiAgentNetworks(MultiAgentSizes{{3, 4}, {2, 2}, 4}, config, false, rng), std::invalid_argument);
}

// SGD on J_C - d with d = 25, lambda_0 = 0.78, lambda_lr = 0.1: J_C = 30, 20, 10 gives
// 0.78 + 0.5 = 1.28, 1.28 - 0.5 = 0.78, max(0, 0.78 - 1.5) = 0.
TEST(MultiAgentFamily, MappoLagMultiplierFollowsTheSgdRuleOnTheTeamCost) {
  const RunConfig config = slot_update_config(ma_config("mappo-lag", {"lambda_lr=0.1", "cost_limit=25"}));
  EXPECT_EQ(config.alg, Algorithm::ppo_lag);
  LagrangeMultipliers multipliers(config);
  const double expected[] = {1.28, 0.78, 0.0};
  const double costs[] = {30.0, 20.0, 10.0};
  for (int k = 0; k < 3; ++k) {
    const std::vector<ConstraintEstimate> constraint{{costs[k], 25.0}};
    EXPECT_NEAR(multipliers.update(constraint).front(), expected[k], 1e-12) << "epoch " << k;
  }
  EXPECT_EQ(slot_update_config(ma_config("mappo")).alg, Algorithm::ppo);
}

// Trains `config` whole into dir/whole, and stopped after one epoch then resumed into dir/split;
// their progress.csv must agree but for the timing columns.
void train_whole_and_resumed(const RunConfig& config, const std::filesystem::path& root) {
  MultiAgentTrainer whole(config, RunDirectory(root / "whole"), MpiContext::single_process(), {});
  ASSERT_TRUE(whole.run().finished);
  TrainerOptions stop;
  stop.stop_after_epochs = 1;
  {
    MultiAgentTrainer first(config, RunDirectory(root / "split"), MpiContext::single_process(), stop);
    EXPECT_EQ(first.run().epochs_completed, 1);
  }
  TrainerOptions resume;
  resume.resume = true;
  MultiAgentTrainer second(config, RunDirectory(root / "split"), MpiContext::single_process(), resume);
  ASSERT_TRUE(second.run().finished);
  EXPECT_EQ(without_times(root / "split" / "progress.csv"), without_times(root / "whole" / "progress.csv"));
}

TEST(MultiAgentFamily, AResumedRunWritesTheUninterruptedRunsFiles) {
  const bsg::testing::TemporaryDirectory dir("multi_agent");
  const RunConfig config = ma_config("mappo-lag");
  train_whole_and_resumed(config, dir.path());
  if (::testing::Test::HasFatalFailure()) return;
  EXPECT_EQ(bsg::testing::read_text_file(dir.path() / "split" / "evaluation.json"),
            bsg::testing::read_text_file(dir.path() / "whole" / "evaluation.json"));
  const auto header = bsg::testing::read_csv_rows(dir.path() / "whole" / "progress.csv").front();
  EXPECT_NE(std::find(header.begin(), header.end(), "agent_1_cost_mean"), header.end());
  EXPECT_NE(std::find(header.begin(), header.end(), "lagrange_multiplier"), header.end());
}

// HAPPO and MACPO: the per-agent PPO Adam (HAPPO) and the epoch's order survive a checkpoint; the
// per-agent columns of the round are written.
void expect_resumed_run_equals_whole(const std::string& alg, const std::string& only_column) {
  const bsg::testing::TemporaryDirectory dir("multi_agent_" + alg);
  const RunConfig config = ma_config(alg);
  train_whole_and_resumed(config, dir.path());
  if (::testing::Test::HasFatalFailure()) return;
  const auto rows = bsg::testing::read_csv_rows(dir.path() / "whole" / "progress.csv");
  const auto& header = rows.front();
  for (const std::string& column : {std::string("agent_1_position"), std::string("agent_0_factor_max"), only_column}) {
    EXPECT_NE(std::find(header.begin(), header.end(), column), header.end()) << column;
  }
  EXPECT_EQ(std::find(header.begin(), header.end(), "lagrange_multiplier"), header.end());
  // Two agents: the positions of every epoch are 0 and 1 in some order, the first agent's factor is 1.
  const auto column = [&](const std::string& name) {
    return static_cast<std::size_t>(std::find(header.begin(), header.end(), name) - header.begin());
  };
  for (std::size_t r = 1; r < rows.size(); ++r) {
    const double p0 = std::stod(rows[r][column("agent_0_position")]);
    const double p1 = std::stod(rows[r][column("agent_1_position")]);
    EXPECT_EQ(p0 + p1, 1.0);
    const std::string first = p0 == 0.0 ? "agent_0_" : "agent_1_";
    EXPECT_EQ(std::stod(rows[r][column(first + "factor_min")]), 1.0);
    EXPECT_EQ(std::stod(rows[r][column(first + "factor_max")]), 1.0);
  }
}

TEST(MultiAgentFamily, AResumedHappoRunWritesTheUninterruptedRunsFiles) {
  expect_resumed_run_equals_whole("happo", "agent_0_step_norm");
}

TEST(MultiAgentFamily, AResumedMacpoRunWritesTheUninterruptedRunsFiles) {
  expect_resumed_run_equals_whole("macpo", "agent_1_constraint_violation");
}

TEST(MultiAgentFamily, ASharedPolicyRunTrains) {
  const bsg::testing::TemporaryDirectory dir("multi_agent_shared");
  MultiAgentTrainer trainer(ma_config("mappo", {"share_policy=true", "epochs=1"}), RunDirectory(dir.path() / "run"),
                            MpiContext::single_process(), {});
  EXPECT_TRUE(trainer.run().finished);
  EXPECT_EQ(trainer.multi_agent().networks().slot_count(), 1);
}

TEST(MultiAgentFamily, EnvAndAlgOfDifferentFamiliesAreRefusedInOneLine) {
  const auto message = [](std::vector<std::string> arguments) {
    RunConfigRequest request;
    request.configs_dir = fs::path(BSG_SOURCE_DIR) / "configs";
    request.set_arguments = std::move(arguments);
    try {
      resolve_training_config(request);
    } catch (const ConfigError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string single = message({"env_id=SafetyBallCircle-v0", "alg=mappo-lag"});
  EXPECT_NE(single.find("single-agent environment"), std::string::npos) << single;
  const std::string multi = message({"env_id=SafetyBallCircle2-v0", "alg=ppo-lag"});
  EXPECT_NE(multi.find("is a multi-agent environment"), std::string::npos) << multi;
  const std::string constraints = message({"env_id=SafetyBallCircle2-v0", "alg=mappo-lag", "constraints=[{terms: all, limit: 3}]"});
  EXPECT_NE(constraints.find("not supported by alg 'mappo-lag'"), std::string::npos) << constraints;
  const std::string shared = message({"env_id=SafetyBallCircle2-v0", "alg=happo", "share_policy=true"});
  EXPECT_NE(shared.find("share_policy must be false"), std::string::npos) << shared;
  for (const std::string& text : {single, multi, constraints, shared}) EXPECT_EQ(text.find('\n'), std::string::npos) << text;
}

}  // namespace multi_agent_family_test
}  // namespace
}  // namespace bsg::algos
