// `--set key=value` arguments of `bsg envs --describe`, `bsg rollout` and
// `bsg bench`: overrides of an environment description (envs/description/env_parameters.h).
#pragma once

#include <string>
#include <vector>

#include "envs/env.h"

namespace bsg::cli {

// "bombs=12" → ("bombs", "12"). Throws std::invalid_argument naming an
// argument without '=' or with an empty key.
envs::EnvOverrides parse_env_set_arguments(const std::vector<std::string>& arguments);

}  // namespace bsg::cli
