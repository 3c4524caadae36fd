// The PID multiplier's configuration keys (lambda_optimizer: PID and the pid_*
// keys of TRPO-L and PDO): the shipped defaults, every bad value rejected with
// the key named, and a key that would have no effect under the chosen rule
// reported instead of ignored.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "../test_support.h"
#include "shipped_request.h"
#include "common/config_error.h"
#include "common/run_config_resolve.h"
#include "common/run_config_yaml.h"

namespace bsg {
namespace {

namespace fs = std::filesystem;
using testing::contains;

using testing::ball_circle_request;

using testing::config_error_of;

TEST(PidConfig, ShippedDefaultsOfBothLagrangianAlgorithms) {
  for (const char* alg : {"lag-trpo", "pdo"}) {
    SCOPED_TRACE(alg);
    const RunConfig config = resolve_run_config(ball_circle_request(alg, {"lambda_optimizer=PID"})).config;
    EXPECT_EQ(config.multiplier.lambda_optimizer, LambdaOptimizer::pid);
    EXPECT_EQ(config.multiplier.pid_kp, 0.1);
    EXPECT_EQ(config.multiplier.pid_ki, 0.005);
    EXPECT_EQ(config.multiplier.pid_kd, 0.0);
    EXPECT_EQ(config.multiplier.pid_d_delay, 10);
    EXPECT_EQ(config.multiplier.pid_delta_p_ema_alpha, 0.0);
    EXPECT_EQ(config.multiplier.pid_delta_d_ema_alpha, 0.0);
    EXPECT_EQ(config.multiplier.pid_lambda_max, 0.0);
  }
}

TEST(PidConfig, OutOfRangeValuesAreRejectedNamingTheKey) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"pid_kp=-0.1", "[0, inf)"},          {"pid_ki=-1", "[0, inf)"},
      {"pid_kd=-2", "[0, inf)"},            {"pid_d_delay=0", "[1, 1000]"},
      {"pid_d_delay=1.5", "an integer"},    {"pid_delta_p_ema_alpha=1", "[0, 1)"},
      {"pid_delta_d_ema_alpha=-0.5", "[0, 1)"}, {"pid_lambda_max=-3", "[0, inf)"},
      {"pid_kp=fast", "a real number"}};
  for (const auto& [setting, valid] : cases) {
    SCOPED_TRACE(setting);
    const std::string m = config_error_of(ball_circle_request("lag-trpo", {"lambda_optimizer=PID", setting}));
    const std::string key = setting.substr(0, setting.find('='));
    EXPECT_TRUE(contains(m, "key '" + key + "'")) << m;
    EXPECT_TRUE(contains(m, "--set " + setting)) << m;
    EXPECT_TRUE(contains(m, valid)) << m;
  }
  const std::string m = config_error_of(ball_circle_request("pdo", {"lambda_optimizer=pid"}));
  EXPECT_TRUE(contains(m, "key 'lambda_optimizer' = 'pid' is not valid; valid values: SGD | Adam | PID")) << m;
}

TEST(PidConfig, PidKeysBelongToTheLagrangianAlgorithmsOnly) {
  for (const char* alg : {"trpo", "cpo", "pcpo"}) {
    const std::string m = config_error_of(ball_circle_request(alg, {"pid_kp=0.5"}));
    EXPECT_TRUE(contains(m, "'pid_kp' does not apply to alg '" + std::string(alg) + "'")) << m;
    EXPECT_TRUE(contains(m, "used by lag-trpo, pdo")) << m;
  }
}

TEST(PidConfig, AKeyWithoutEffectUnderTheChosenRuleIsAnError) {
  std::string m = config_error_of(ball_circle_request("lag-trpo", {"pid_kd=0.5"}));
  EXPECT_TRUE(contains(m, "--set pid_kd=0.5: key 'pid_kd' applies only with lambda_optimizer: PID")) << m;
  EXPECT_TRUE(contains(m, "lambda_optimizer is SGD")) << m;
  m = config_error_of(ball_circle_request("pdo", {"lambda_optimizer=PID", "lambda_lr=0.1"}));
  EXPECT_TRUE(contains(m, "--set lambda_lr=0.1: key 'lambda_lr' has no effect with lambda_optimizer: PID")) << m;
  EXPECT_TRUE(contains(m, "pid_ki")) << m;
  // The algorithm file's own values are fine: a resolved config lists every key.
  EXPECT_NO_THROW(resolve_run_config(ball_circle_request("lag-trpo", {"pid_kp=0.1", "lambda_lr=0.05"})));
  EXPECT_NO_THROW(resolve_run_config(ball_circle_request("lag-trpo", {"lambda_optimizer=PID", "lambda_lr=0.05"})));
}

TEST(PidConfig, AResolvedPidConfigReadsBackAsARunFile) {
  // The sweep writes the resolved config (every key) as run.yaml and trains from it.
  const RunConfig config =
      resolve_run_config(ball_circle_request("lag-trpo", {"lambda_optimizer=PID", "pid_kp=0.25", "pid_kd=0.125",
                                              "pid_d_delay=3", "pid_delta_p_ema_alpha=0.5",
                                              "pid_delta_d_ema_alpha=0.75", "pid_lambda_max=8"}))
          .config;
  const testing::TemporaryDirectory dir;
  const fs::path run_file = dir.path() / "run.yaml";
  testing::write_text_file(run_file, to_yaml(config));
  RunConfigRequest request;
  request.configs_dir = fs::path(BSG_SOURCE_DIR) / "configs";
  request.run_file = run_file;
  const RunConfig again = resolve_run_config(request).config;
  EXPECT_EQ(again, config);
  EXPECT_EQ(again.multiplier.pid_d_delay, 3);
  EXPECT_EQ(again.multiplier.pid_delta_d_ema_alpha, 0.75);
  EXPECT_EQ(again.multiplier.pid_lambda_max, 8.0);
}

}  // namespace
}  // namespace bsg
