// A run of the on-policy family (on_policy_family.h) in the run skeleton (trainer.h): what
// make_trainer builds for the trust-region and first-order algorithms, and what tests and the
// training benchmark hold to read the actor-critic and the algorithm.
#pragma once

#include <memory>

#include "algos/training/on_policy_family.h"
#include "algos/training/trainer.h"

namespace bsg::algos {

class OnPolicyTrainer final : public Trainer {
 public:
  // With the run's environment (run_environment.h).
  OnPolicyTrainer(const RunConfig& config, RunDirectory directory, const MpiContext& mpi, TrainerOptions options);
  // With a given environment (tests use scripted ones).
  OnPolicyTrainer(const RunConfig& config, RunDirectory directory, const MpiContext& mpi, TrainerOptions options,
                  std::unique_ptr<envs::Env> env);

  const OnPolicyFamily& on_policy() const { return static_cast<const OnPolicyFamily&>(family()); }
  const ActorCritic& actor_critic() const { return on_policy().actor_critic(); }
  const OnPolicyAlgorithm& algorithm() const { return on_policy().algorithm(); }
};

}  // namespace bsg::algos
