#include "algos/training/off_policy_trainer.h"

#include "algos/training/run_environment.h"

namespace bsg::algos {
namespace {

std::vector<std::unique_ptr<envs::Env>> make_run_envs(const RunConfig& config) {
  std::vector<std::unique_ptr<envs::Env>> envs;
  for (int j = 0; j < config.off_policy.num_envs; ++j) envs.push_back(make_run_env(config));
  return envs;
}

}  // namespace

OffPolicyTrainer::OffPolicyTrainer(const RunConfig& config, RunDirectory directory, const MpiContext& mpi,
                                   TrainerOptions options)
    : OffPolicyTrainer(config, std::move(directory), mpi, std::move(options), make_run_envs(config)) {}

OffPolicyTrainer::OffPolicyTrainer(const RunConfig& config, RunDirectory directory, const MpiContext& mpi,
                                   TrainerOptions options, std::vector<std::unique_ptr<envs::Env>> envs)
    : Trainer(config, directory, mpi, std::move(options),
              std::make_unique<OffPolicyFamily>(config, directory, mpi, std::move(envs))) {}

}  // namespace bsg::algos
