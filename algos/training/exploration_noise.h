// The exploration noise sigma of each epoch (docs/algorithms.md#exploration-noise): the
// annealing schedule of the config (or the fixed 0.5 without it), held at or above
// exploration_std_floor. The trainer sets it at the start of every epoch; the
// sampled evaluation (docs/reproducing.md#evaluation) uses the last epoch's.
#pragma once

#include "algos/training/evaluation_actions.h"
#include "algos/core/gaussian_policy.h"
#include "common/run_config.h"

namespace bsg::algos {

// sigma of epoch `epoch` in [0, config.epochs): max(schedule, floor). Throws
// std::invalid_argument for an epoch outside the run. Meaningless with a learned
// log sigma (the update sets sigma then; run_config_checks rejects a floor with it).
double exploration_std(const RunConfig& config, int epoch);

// Gives `policy` the sigma it was last trained with, the sigma of epoch epochs_completed - 1
// (of epoch 0 before any epoch), for the sampled evaluation; a learned log sigma is left as
// the checkpoint has it.
void set_last_epoch_std(const RunConfig& config, int epochs_completed, GaussianPolicy& policy);

// The evaluation's actions: sampled with sampled_evaluation, else the mean (the original's).
EvaluationActions evaluation_actions(const RunConfig& config);

}  // namespace bsg::algos
