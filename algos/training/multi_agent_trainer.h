// A run of the multi-agent family (multi_agent_family.h) in the run skeleton (trainer.h): what
// make_trainer builds for mappo, mappo-lag, happo and macpo.
#pragma once

#include <memory>

#include "algos/training/multi_agent_family.h"
#include "algos/training/trainer.h"
#include "envs/multi_agent_env.h"

namespace bsg::algos {

// The run's multi-agent environment, registered as env_id, with its physics model.
std::unique_ptr<envs::MultiAgentEnv> make_run_multi_agent_env(const RunConfig& config);

class MultiAgentTrainer final : public Trainer {
 public:
  MultiAgentTrainer(const RunConfig& config, RunDirectory directory, const MpiContext& mpi, TrainerOptions options);

  const MultiAgentFamily& multi_agent() const { return static_cast<const MultiAgentFamily&>(family()); }
};

}  // namespace bsg::algos
