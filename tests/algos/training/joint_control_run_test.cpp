// A single-agent learner controlling every agent of a multi-agent id (joint_control,
// docs/multi_agent.md#one-learner-for-the-whole-team): the run trains on the joint environment,
// config.yaml names the key so that a resume builds the same environment, every other run's
// config.yaml stays as before the key, and misuses are refused in one line.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "../../test_support.h"
#include "algos/training/on_policy_trainer.h"
#include "algos/training/run_environment.h"
#include "algos/training/run_start.h"
#include "common/config_error.h"
#include "common/mpi_context.h"
#include "common/run_config_resolve.h"
#include "common/run_config_yaml.h"

namespace bsg::algos {
namespace {
// Its own names apart from the other files of its test batch (tests/CMakeLists.txt).
namespace joint_control_run_test {

namespace fs = std::filesystem;

RunConfig resolved(std::vector<std::string> arguments) {
  RunConfigRequest request;
  request.configs_dir = fs::path(BSG_SOURCE_DIR) / "configs";
  request.set_arguments = std::move(arguments);
  return resolve_training_config(request);
}

std::string refusal(std::vector<std::string> arguments) {
  try {
    resolved(std::move(arguments));
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "no error";
}

std::string text_of(const fs::path& path) {
  std::ifstream in(path);
  std::ostringstream out;
  out << in.rdbuf();
  return out.str();
}

TEST(JointControlRun, PpoLagTrainsOnTheJointEnvironmentAndConfigYamlKeepsTheKey) {
  const RunConfig config = resolved({"env_id=SafetyBallCircle2-v0", "alg=ppo-lag", "joint_control=true", "epochs=1",
                                     "steps_per_epoch=500", "eval_episodes=2", "update_iters=2"});
  // The joint environment: two agents of 10 observations and 2 actions each, d per agent.
  const std::unique_ptr<envs::Env> env = make_run_env(config);
  EXPECT_EQ(env->spec().observation_dim, 20);
  EXPECT_EQ(env->spec().action_dim, 4);
  EXPECT_EQ(config.cost_limit, 25.0);
  const bsg::testing::TemporaryDirectory directory;
  const RunDirectory run(directory.path() / "run");
  OnPolicyTrainer trainer(config, run, MpiContext::single_process(), {});
  EXPECT_TRUE(trainer.run().finished);
  EXPECT_NE(text_of(run.config()).find("joint_control: true"), std::string::npos);
  const RunConfig resumed = resumed_training_config(run);
  EXPECT_TRUE(resumed.joint_control);
  EXPECT_EQ(resumed, config);
  const std::vector<double> lengths =
      bsg::testing::read_csv_columns(run.root / "progress.csv").at("episode_length_mean");
  EXPECT_EQ(lengths.at(0), 250.0);  // the team's episodes, SafetyBallCircle2-v0's 250 steps
}

TEST(JointControlRun, ARunWithoutTheKeyWritesConfigYamlAsBefore) {
  const RunConfig config = resolved({"env_id=SafetyBallCircle-v0", "alg=ppo-lag"});
  EXPECT_FALSE(config.joint_control);
  EXPECT_EQ(to_yaml(config).find("joint_control"), std::string::npos);
}

TEST(JointControlRun, MisusesAreRefusedInOneLine) {
  const std::string single = refusal({"env_id=SafetyBallCircle-v0", "alg=ppo-lag", "joint_control=true"});
  EXPECT_NE(single.find("joint_control: true needs a multi-agent env_id"), std::string::npos) << single;
  const std::string hint = refusal({"env_id=SafetyBallCircle2-v0", "alg=ppo-lag"});
  EXPECT_NE(hint.find("set joint_control: true"), std::string::npos) << hint;
  const std::string family = refusal({"env_id=SafetyBallCircle2-v0", "alg=mappo-lag", "joint_control=true"});
  EXPECT_NE(family.find("joint_control"), std::string::npos) << family;
  const std::string block =
      refusal({"env_id=SafetyBallCircle2-v0", "alg=ppo-lag", "joint_control=true", "env={bodies: 3}"});
  EXPECT_NE(block.find("env"), std::string::npos) << block;
  for (const std::string& text : {single, hint, family, block}) {
    EXPECT_NE(text, "no error");
    EXPECT_EQ(text.find('\n'), std::string::npos) << text;
  }
}

}  // namespace joint_control_run_test
}  // namespace
}  // namespace bsg::algos
