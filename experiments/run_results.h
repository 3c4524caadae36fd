// What a run directory (run_directory.h) says about its run: whether it has
// finished (evaluation.json exists), can be resumed (a checkpoint exists) or
// must start afresh, and its evaluation results.
#pragma once

#include <filesystem>
#include <optional>
#include <vector>

#include "algos/training/run_directory.h"

namespace bsg::experiments {

enum class RunState { fresh, resumable, finished };
const char* to_string(RunState state);

RunState run_state(const algos::RunDirectory& directory);

// What a finished run's evaluation.json says. (Not algos/training/run_evaluation.h's
// RunEvaluation, which evaluates a run: two classes of one name in one namespace
// broke the One Definition Rule.)
struct RecordedEvaluation {
  double mean_return = 0.0;  // J
  double mean_cost = 0.0;    // H
  long long episodes = 0;
  // Safety during training (absent in runs from before it: NaN / empty).
  double cost_rate = 0.0;                // training cost / training steps
  std::vector<double> constraint_costs{};  // H_i of the "constraints" list, in order
  std::vector<double> constraint_limits{};  // d_i
};

// Epochs logged so far: the data rows of progress.csv (0 if it does not exist).
int logged_epochs(const algos::RunDirectory& directory);

// evaluation.json of a finished run; nullopt if it does not exist. Throws
// std::runtime_error naming the file if it is malformed. A non-finite mean
// (written as null) reads as NaN.
std::optional<RecordedEvaluation> read_run_evaluation(const algos::RunDirectory& directory);

// One number per line (returns.csv, costs.csv); throws std::runtime_error
// naming the file and line if it is missing or holds something else.
std::vector<double> read_value_per_line(const std::filesystem::path& path);

}  // namespace bsg::experiments
