// The collection behind `bsg collect` and `bsg dataset make`: policy specs,
// the environment, the constraints and the file (docs/datasets.md#collecting).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace bsg::cli {

struct CollectArguments {
  std::string out;
  std::string env_id;
  std::vector<std::string> set_arguments;
  std::vector<std::string> policies;  // "random" or a run directory, optionally "=SHARE"
  std::optional<std::int64_t> episodes;
  std::optional<std::int64_t> transitions;
  std::uint64_t seed = 0;
  std::string actions = "sampled";
  std::optional<double> cost_limit;
  std::string physics = "faithful";
  bool force = false;
};

struct CollectSummary {
  std::size_t transitions = 0;
  long long episodes = 0;
  std::string env_id;
  double seconds = 0.0;
  std::uintmax_t bytes = 0;
};

// Collects and writes args.out (under a temporary name, then renamed). Throws
// with one line naming the fault: bad counts or shares, an existing file
// without force, an unknown environment, a checkpoint of another environment
// or with other constraints.
CollectSummary collect_to_file(const CollectArguments& args);

}  // namespace bsg::cli
