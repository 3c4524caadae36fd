#include "algos/training/multi_agent_trainer.h"

namespace bsg::algos {

std::unique_ptr<envs::MultiAgentEnv> make_run_multi_agent_env(const RunConfig& config) {
  return envs::make_multi_agent(config.env_id, {.physics = config.physics});
}

MultiAgentTrainer::MultiAgentTrainer(const RunConfig& config, RunDirectory directory, const MpiContext& mpi,
                                     TrainerOptions options)
    : Trainer(config, std::move(directory), mpi, std::move(options),
              std::make_unique<MultiAgentFamily>(config, mpi, make_run_multi_agent_env(config))) {}

}  // namespace bsg::algos
