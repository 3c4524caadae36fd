// A run of the offline family (offline_family.h) in the run skeleton (trainer.h): what make_trainer
// builds for bc-all and bc-safe, and what tests hold to read the algorithm.
#pragma once

#include <memory>

#include "algos/training/offline_family.h"
#include "algos/training/trainer.h"

namespace bsg::algos {

class OfflineTrainer final : public Trainer {
 public:
  // Evaluating on the run's environment (run_environment.h).
  OfflineTrainer(const RunConfig& config, RunDirectory directory, const MpiContext& mpi, TrainerOptions options);
  // Evaluating on a given environment (tests).
  OfflineTrainer(const RunConfig& config, RunDirectory directory, const MpiContext& mpi, TrainerOptions options,
                 std::unique_ptr<envs::Env> env);

  const OfflineFamily& offline() const { return static_cast<const OfflineFamily&>(family()); }
};

}  // namespace bsg::algos
