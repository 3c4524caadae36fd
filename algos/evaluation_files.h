// The evaluation files of a run directory (docs/reproducing.md#evaluation): returns.csv and
// costs.csv with one value per line and no header, and evaluation.json:
//   {"mean_return": J, "mean_cost": H, "episodes": n, "mean_length": L}
#pragma once

#include <string>

#include "algos/evaluation.h"
#include "algos/run_directory.h"

namespace bsg {

void write_evaluation_files(const RunDirectory& directory, const EvaluationSummary& summary);

// The JSON object of evaluation.json; with `per_episode` also the arrays
// "returns", "costs" and "lengths".
std::string evaluation_json(const EvaluationSummary& summary, bool per_episode);

}  // namespace bsg
