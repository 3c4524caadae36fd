// The environment of a run: env_id's description with the run's `env:` block
// applied (envs/description/env_parameters.h), so that training, --resume and `bsg eval`
// build the same environment from the run directory's config.yaml.
#pragma once

#include <memory>

#include "common/run_config.h"
#include "envs/env.h"

namespace bsg::algos {

// env_id's description with config.env applied; throws ConfigError naming the
// env: key and value at fault, or saying that a joint_control run has none.
envs::EnvDescription run_env_description(const RunConfig& config);

// The run's environment with its physics model; with joint_control the multi-agent env_id
// seen as one agent (envs/joint_control_env.h).
std::unique_ptr<envs::Env> make_run_env(const RunConfig& config);

// For a new run with an env: block: replaces the block by every key of the
// resolved description (so config.yaml and the checkpoint hold all of it, and
// later changes of a default cannot change the run), and lets max_ep_len and
// cost_limit follow max_episode_steps and cost_limit when the block sets them.
// A run without an env: block is left as it is (its env_id names a standard
// description).
void resolve_env_block(RunConfig& config);

}  // namespace bsg::algos
