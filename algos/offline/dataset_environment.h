// The environment a dataset was collected on, rebuilt from the file's
// `env_description` attribute (the description as YAML, envs::to_yaml), so
// that a policy trained on the file is evaluated on the same environment.
#pragma once

#include "algos/offline/offline_dataset.h"
#include "envs/env.h"

namespace bsg::algos {

// Throws std::invalid_argument naming the attribute if it is missing or does
// not describe an environment.
envs::EnvDescription dataset_env_description(const OfflineDataset& dataset);

}  // namespace bsg::algos
