// A collection as a whole (docs/datasets.md#collecting): which policies act
// and with what shares, on which environment, with which constraints, and the
// file it writes with the attributes that say how it was made. `bsg collect`
// and `bsg dataset make` fill a request and print its summary; the rules are
// here. The environment is --env's (with its overrides) or, without one, the
// first checkpoint's; every checkpoint must have been trained on it, id and
// parameters alike. The constraints are the checkpoints' (their terms must
// agree, their limits may differ), else the environment's whole cost.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "algos/training/evaluation_actions.h"
#include "common/physics_model.h"
#include "envs/env.h"

namespace bsg::algos {

// One policy of a collection: "random" (uniform actions in the declared
// bounds) or a run directory, and its relative weight.
struct PolicySpec {
  std::string source;
  double share = 1.0;  // > 0
};

// "runs/x=3" -> (runs/x, 3); "random" -> (random, 1). Throws
// std::invalid_argument naming `text` ("--policy TEXT: ...") for a share that
// is not a positive finite number or no policy before the '='.
PolicySpec parse_policy_spec(const std::string& text);

struct CollectionRequest {
  std::string out;                   // the HDF5 file
  std::string env_id;                // empty: the first checkpoint's environment
  envs::EnvOverrides env_overrides;  // changes of env_id's description (only with env_id)
  std::vector<PolicySpec> policies;  // in turn, in this order
  std::optional<std::int64_t> episodes;     // exactly one of episodes and transitions
  std::optional<std::int64_t> transitions;
  std::uint64_t seed = 0;
  EvaluationActions actions = EvaluationActions::sampled;
  std::optional<double> cost_limit;  // stored for the normalised cost; default: the constraint's limit
  PhysicsModel physics = PhysicsModel::kFaithful;
  bool force = false;                // replace an existing file
  // Empty: the file's `policies` attribute names each checkpoint as given;
  // else relative to this directory (bsg dataset make: its --out), so that a
  // dataset rebuilt in another place has the same bytes.
  std::string checkpoint_names_relative_to;
};

struct CollectionSummary {
  std::size_t transitions = 0;
  long long episodes = 0;
  std::string env_id;
  double seconds = 0.0;
  std::uintmax_t bytes = 0;
};

// "sampled" or "mean", as the file's `actions` attribute and --actions spell them.
std::string actions_name(EvaluationActions actions);

// Collects and writes request.out (under a temporary name, then renamed; its
// folder is made if missing). Throws std::invalid_argument (or the loader's
// error) with one line naming the fault: not exactly one of the counts, a
// count < 1, an existing file without force, overrides without env_id, no
// environment, an unknown environment, a checkpoint of another environment
// or with other constraints.
CollectionSummary collect_to_file(const CollectionRequest& request);

}  // namespace bsg::algos
