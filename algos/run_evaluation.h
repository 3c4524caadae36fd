// `bsg eval DIR`: re-runs the deterministic evaluation (docs/reproducing.md#evaluation) of a run
// directory's latest checkpoint, without writing anything.
#pragma once

#include <optional>

#include "algos/evaluation.h"
#include "algos/run_directory.h"
#include "common/mpi_context.h"

namespace bsg {

struct RunEvaluation {
  EvaluationSummary summary;  // rank 0 only
  int epochs_completed = 0;   // of the checkpoint
  int epochs = 0;             // of the run's config
};

// `episodes` overrides the config's eval_episodes. Collective. Throws naming
// the directory or file at fault (not a run directory, corrupt checkpoint).
RunEvaluation evaluate_run_directory(const RunDirectory& directory, std::optional<int> episodes,
                                     const MpiContext& mpi);

}  // namespace bsg
