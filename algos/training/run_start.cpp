#include "algos/training/run_start.h"

#include <new>
#include <stdexcept>
#include <string>

#include "algos/offline/dataset_location.h"
#include "algos/training/make_trainer.h"
#include "algos/training/run_environment.h"
#include "common/config_error.h"
#include "common/run_config_checks.h"
#include "common/run_config_yaml.h"
#include "envs/env.h"

namespace bsg::algos {

RunConfig resolve_training_config(RunConfigRequest request) {
  request.valid_env_ids = envs::registered_ids();
  RunConfig config = resolve_run_config(request).config;
  resolve_env_block(config);
  if (is_offline(config.alg) && !config.offline.dataset.empty()) {
    // config.yaml records the file itself, so a resumed run reads what the run began with.
    config.offline.dataset = locate_dataset(config.offline.dataset, config.env_id).string();
  }
  return config;
}

RunConfig resumed_training_config(const RunDirectory& directory) {
  check_is_run_directory(directory);
  return load_resolved_run_config(directory.config(), envs::registered_ids());
}

void check_before_training(const RunConfig& config, int num_ranks) {
  check_run_config_for_ranks(config, num_ranks);
  std::unique_ptr<envs::Env> env;
  try {
    env = envs::make(config.env_id, {.physics = config.physics});
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
    const std::unique_ptr<envs::Env> env = envs::make(config.env_id, {.physics = config.physics});
    const TrainingMemoryEstimate estimate =
        estimate_training_memory(config, env->spec().observation_dim, env->spec().action_dim, mpi.size());
    throw std::runtime_error("out of memory while allocating the networks (hidden_sizes) and " +
                             training_buffer(config, mpi.size()).description + ": the estimate is " +
                             format_bytes(estimate.bytes) + " per rank of " + available_memory().description);
  }
}

}  // namespace bsg::algos
