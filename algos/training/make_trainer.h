// The one place that chooses a run's family of learners from its config: the trust-region and
// first-order algorithms train in the on-policy family, SAC, TD3, DDPG and their -lag forms in the
// off-policy one, BC-All and BC-Safe in the offline one. `bsg train`, the training benchmark and anything later ask here.
#pragma once

#include <memory>

#include "algos/training/trainer.h"

namespace bsg::algos {

std::unique_ptr<Trainer> make_trainer(const RunConfig& config, const RunDirectory& directory, const MpiContext& mpi,
                                      const TrainerOptions& options);

}  // namespace bsg::algos
