#include "algos/training/offline_trainer.h"

#include "algos/training/run_environment.h"

namespace bsg::algos {

OfflineTrainer::OfflineTrainer(const RunConfig& config, RunDirectory directory, const MpiContext& mpi,
                               TrainerOptions options)
    : OfflineTrainer(config, std::move(directory), mpi, std::move(options), make_run_env(config)) {}

OfflineTrainer::OfflineTrainer(const RunConfig& config, RunDirectory directory, const MpiContext& mpi,
                               TrainerOptions options, std::unique_ptr<envs::Env> env)
    : Trainer(config, std::move(directory), mpi, std::move(options),
              std::make_unique<OfflineFamily>(config, mpi, std::move(env))) {}

}  // namespace bsg::algos
