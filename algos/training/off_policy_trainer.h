// A run of the off-policy family (off_policy_family.h) in the run skeleton (trainer.h): what
// make_trainer builds for SAC, TD3, DDPG and their -lag forms, and what tests hold to read the
// learner and the replay buffer.
#pragma once

#include <memory>
#include <vector>

#include "algos/training/off_policy_family.h"
#include "algos/training/trainer.h"

namespace bsg::algos {

class OffPolicyTrainer final : public Trainer {
 public:
  // With num_envs of the run's environments (run_environment.h).
  OffPolicyTrainer(const RunConfig& config, RunDirectory directory, const MpiContext& mpi, TrainerOptions options);
  // With given environments (tests); `envs` must hold num_envs of them.
  OffPolicyTrainer(const RunConfig& config, RunDirectory directory, const MpiContext& mpi, TrainerOptions options,
                   std::vector<std::unique_ptr<envs::Env>> envs);

  const OffPolicyFamily& off_policy() const { return static_cast<const OffPolicyFamily&>(family()); }
  const OffPolicyLearner& learner() const { return off_policy().learner(); }
  const ReplayBuffer& buffer() const { return off_policy().buffer(); }
};

}  // namespace bsg::algos
