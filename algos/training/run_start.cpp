#include "algos/training/run_start.h"

#include <algorithm>
#include <new>
#include <stdexcept>
#include <string>

#include "algos/training/dataset_location.h"
#include "algos/training/make_trainer.h"
#include "algos/training/run_environment.h"
#include "common/config_error.h"
#include "common/run_config_checks.h"
#include "common/run_config_yaml.h"
#include "envs/env.h"
#include "envs/multi_agent_env.h"

namespace bsg::algos {

std::vector<std::string> training_env_ids() {
  std::vector<std::string> ids = envs::registered_ids();
  const std::vector<std::string> multi = envs::multi_agent_ids();
  ids.insert(ids.end(), multi.begin(), multi.end());
  std::sort(ids.begin(), ids.end());
  return ids;
}

void check_env_matches_family(const RunConfig& config) {
  const std::vector<std::string> multi = envs::multi_agent_ids();
  const bool multi_agent_env = std::find(multi.begin(), multi.end(), config.env_id) != multi.end();
  const std::string alg(to_string(config.alg));
  if (is_multi_agent(config.alg) && !multi_agent_env) {
    throw ConfigError("alg '" + alg + "' trains several agents, but env_id '" + config.env_id +
                      "' is a single-agent environment; use a multi-agent id (`bsg envs --multi-agent`), e.g. "
                      "SafetyBallCircle2-v0");
  }
  if (!is_multi_agent(config.alg) && multi_agent_env && !config.joint_control) {
    throw ConfigError("env_id '" + config.env_id + "' is a multi-agent environment, but alg '" + alg +
                      "' trains one agent; use alg mappo, mappo-lag, happo or macpo, or set joint_control: true "
                      "for one policy controlling every agent");
  }
  if (config.joint_control && !multi_agent_env) {
    throw ConfigError("joint_control: true needs a multi-agent env_id (`bsg envs --multi-agent`), but '" +
                      config.env_id + "' is a single-agent environment");
  }
  if (config.joint_control && !config.env.empty()) {
    throw ConfigError("an env: block is not supported with joint_control: true (a multi-agent id takes none)");
  }
  if (is_sequential_multi_agent(config.alg) && config.multi_agent.share_policy) {
    throw ConfigError("alg '" + alg + "' updates each agent's own policy in turn; share_policy must be false");
  }
}

RunConfig resolve_training_config(RunConfigRequest request) {
  request.valid_env_ids = training_env_ids();
  RunConfig config = resolve_run_config(request).config;
  check_env_matches_family(config);
  resolve_env_block(config);
  if (is_offline(config.alg) && !config.offline.dataset.empty()) {
    // config.yaml records the file itself, so a resumed run reads what the run began with.
    config.offline.dataset = locate_dataset(config.offline.dataset, config.env_id).string();
  }
  return config;
}

RunConfig resumed_training_config(const RunDirectory& directory) {
  check_is_run_directory(directory);
  return load_resolved_run_config(directory.config(), training_env_ids());
}

void check_before_training(const RunConfig& config, int num_ranks) {
  check_run_config_for_ranks(config, num_ranks);
  check_env_matches_family(config);
  if (is_multi_agent(config.alg)) {
    std::unique_ptr<envs::MultiAgentEnv> env;
    try {
      env = envs::make_multi_agent(config.env_id, {.physics = config.physics});
    } catch (const std::invalid_argument& e) {
      throw ConfigError("physics = " + std::string(to_string(config.physics)) + ": " + e.what());
    }
    // The largest agent's sizes, times the agents (each keeps a buffer of the epoch's steps).
    const envs::MultiAgentSpec& spec = env->spec();
    const int observation_dim = *std::max_element(spec.observation_dims.begin(), spec.observation_dims.end());
    const int action_dim = *std::max_element(spec.action_dims.begin(), spec.action_dims.end());
    check_training_memory(config, spec.agent_count() * std::max(observation_dim, spec.state_dim),
                          spec.agent_count() * action_dim, num_ranks, available_memory());
    return;
  }
  std::unique_ptr<envs::Env> env;
  try {
    env = config.joint_control ? make_run_env(config) : envs::make(config.env_id, {.physics = config.physics});
  } catch (const std::invalid_argument& e) {
    throw ConfigError("physics = " + std::string(to_string(config.physics)) + ": " + e.what());
  }
  check_training_memory(config, env->spec().observation_dim, env->spec().action_dim, num_ranks, available_memory());
}

std::unique_ptr<Trainer> allocate_trainer(const RunConfig& config, const RunDirectory& directory,
                                          const MpiContext& mpi, const TrainerOptions& options) {
  try {
    return make_trainer(config, directory, mpi, options);
  } catch (const std::bad_alloc&) {
    if (is_multi_agent(config.alg)) {
      throw std::runtime_error("out of memory while allocating the multi-agent networks (hidden_sizes) and " +
                               training_buffer(config, mpi.size()).description);
    }
    const std::unique_ptr<envs::Env> env =
        config.joint_control ? make_run_env(config) : envs::make(config.env_id, {.physics = config.physics});
    const TrainingMemoryEstimate estimate =
        estimate_training_memory(config, env->spec().observation_dim, env->spec().action_dim, mpi.size());
    throw std::runtime_error("out of memory while allocating the networks (hidden_sizes) and " +
                             training_buffer(config, mpi.size()).description + ": the estimate is " +
                             format_bytes(estimate.bytes) + " per rank of " + available_memory().description);
  }
}

}  // namespace bsg::algos
