#include "algos/training/run_environment.h"

#include <algorithm>
#include <stdexcept>

#include "common/config_error.h"
#include "envs/joint_control_env.h"
#include "envs/multi_agent_env.h"

namespace bsg::algos {

envs::EnvDescription run_env_description(const RunConfig& config) {
  if (config.joint_control) {
    throw ConfigError("env_id " + config.env_id +
                      " controlled jointly (joint_control: true) is a multi-agent environment: it has no "
                      "single-agent description");
  }
  try {
    return envs::describe(config.env_id, config.env);
  } catch (const std::invalid_argument& e) {
    throw ConfigError(e.what());
  }
}

std::unique_ptr<envs::Env> make_run_env(const RunConfig& config) {
  if (config.joint_control) {
    return envs::make_joint_control(envs::make_multi_agent(config.env_id, {.physics = config.physics}));
  }
  return envs::make(run_env_description(config), {.physics = config.physics});
}

void resolve_env_block(RunConfig& config) {
  if (config.env.empty()) return;
  const envs::EnvDescription description = run_env_description(config);
  const auto sets = [&](const char* key) {
    return std::any_of(config.env.begin(), config.env.end(), [&](const auto& p) { return p.first == key; });
  };
  if (sets("max_episode_steps")) config.max_ep_len = description.max_episode_steps;
  if (sets("cost_limit")) config.cost_limit = description.cost_limit;
  config.env = envs::to_env_overrides(description);
}

}  // namespace bsg::algos
