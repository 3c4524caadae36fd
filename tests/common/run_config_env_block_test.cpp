// The run key `env`: a block of environment parameters in a run file, from
// `--set env.key=value`, merged over layers, written back (only when present)
// and read again; run directories written before the key load without it.
#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "common/config_entries.h"
#include "common/config_error.h"
#include "common/run_config.h"
#include "common/run_config_schema.h"
#include "common/run_config_yaml.h"

namespace bsg {
namespace {

using Pairs = std::vector<std::pair<std::string, std::string>>;

RunConfig apply(RunConfig config, const std::string& key, const std::string& yaml) {
  set_config_value(config, *find_config_key(key), YAML::Load(yaml), "test");
  return config;
}

TEST(RunConfigEnvBlock, AMappingBecomesOrderedPairsAndLaterLayersChangeSingleKeys) {
  RunConfig config = apply(RunConfig{}, "env", "{bombs: 12, apples: 4}");
  EXPECT_EQ(config.env, (Pairs{{"bombs", "12"}, {"apples", "4"}}));
  config = apply(config, "env", "{apples: 6, zones: 0}");
  EXPECT_EQ(config.env, (Pairs{{"bombs", "12"}, {"apples", "6"}, {"zones", "0"}}));
}

TEST(RunConfigEnvBlock, SetEnvDotKeyIsOneParameter) {
  const ConfigEntry entry = parse_set_argument("env.bombs=12");
  EXPECT_EQ(entry.key, "env");
  RunConfig config;
  set_config_value(config, *find_config_key("env"), entry.value, entry.origin);
  EXPECT_EQ(config.env, (Pairs{{"bombs", "12"}}));
}

TEST(RunConfigEnvBlock, ANonMappingIsAnErrorNamingTheKey) {
  try {
    apply(RunConfig{}, "env", "[1, 2]");
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("'env'"), std::string::npos) << e.what();
  }
}

TEST(RunConfigEnvBlock, WrittenOnlyWhenPresentAndReadBack) {
  RunConfig config;
  EXPECT_EQ(to_yaml(config).find("\nenv:"), std::string::npos);  // as before the key existed
  const RunConfig plain = run_config_from_yaml(to_yaml(config), "config.yaml", {});
  EXPECT_TRUE(plain.env.empty());
  config.env = {{"bombs", "12"}, {"name", "Gather: 12 bombs"}};  // the emitter quotes what YAML would misread
  const std::string text = to_yaml(config);
  EXPECT_NE(text.find("\nenv: {bombs: 12, name: \"Gather: 12 bombs\"}"), std::string::npos) << text;
  EXPECT_EQ(run_config_from_yaml(text, "config.yaml", {}).env, config.env);
}

}  // namespace
}  // namespace bsg
