// `bsg bench --train`: seconds per training epoch, split into collection,
// policy update and value fits, measured by running the real trainer for a
// few epochs into a temporary run directory (no evaluation). Works under
// mpirun (rank 0 prints). Speed-ups are compared as ratios of two such runs
// made one after the other on the same machine (e.g. --set dtype=float64
// against the default).
#pragma once

#include <string>
#include <vector>

namespace bsg::cli {

struct TrainBenchArguments {
  std::string env_id = "SafetyBallCircle-v0";
  std::string alg = "lag-trpo";
  int epochs = 5;
  std::vector<std::string> set_arguments;  // key=value, applied after the above
  bool json = false;
};

// Prints one line per epoch and the medians (or one JSON object); returns the exit code.
int run_train_benchmark(const TrainBenchArguments& args);

}  // namespace bsg::cli
