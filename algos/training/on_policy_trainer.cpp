#include "algos/training/on_policy_trainer.h"

#include "algos/training/run_environment.h"

namespace bsg::algos {

OnPolicyTrainer::OnPolicyTrainer(const RunConfig& config, RunDirectory directory, const MpiContext& mpi,
                                 TrainerOptions options)
    : OnPolicyTrainer(config, std::move(directory), mpi, std::move(options), make_run_env(config)) {}

OnPolicyTrainer::OnPolicyTrainer(const RunConfig& config, RunDirectory directory, const MpiContext& mpi,
                                 TrainerOptions options, std::unique_ptr<envs::Env> env)
    : Trainer(config, std::move(directory), mpi, std::move(options),
              std::make_unique<OnPolicyFamily>(config, mpi, std::move(env))) {}

}  // namespace bsg::algos
