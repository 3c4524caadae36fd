// Rolling policies out into an offline dataset (docs/datasets.md#collecting):
// the policies of a collection in turn, each for its share of the episodes or
// of the transitions. Episode e of the whole collection (counted from 0 over
// every policy) resets the environment with derive_seed(seed, environment, 0, e)
// and restarts its policy's stream with derive_seed(seed, action_noise, 0, e),
// so that every episode is a function of (seed, e) alone. Actions are clipped
// to the environment's declared bounds before the step, and stored clipped.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "algos/core/constraint_costs.h"
#include "algos/offline/collection_policy.h"
#include "algos/offline/offline_dataset.h"
#include "envs/env.h"

namespace bsg::algos {

enum class CollectionUnit { episodes, transitions };

struct CollectionPlan {
  CollectionUnit unit = CollectionUnit::episodes;
  std::int64_t count = 0;  // episodes or transitions in all, >= 1
  std::uint64_t seed = 0;
};

struct SharedPolicy {
  CollectionPolicy* policy = nullptr;
  double share = 1.0;  // > 0; shares are relative weights
};

// `total` split in proportion to `shares` by the largest remainder (ties to
// the earlier policy): the parts sum to `total`. Throws std::invalid_argument
// for a negative total, no shares, or a share that is not a positive finite number.
std::vector<std::int64_t> split_by_shares(std::int64_t total, const std::vector<double>& shares);

// Collects the dataset. `costs` chooses the constraints (with m > 1 the
// constraint_costs matrix, named `constraint_names`, is filled and `costs` is
// their sum; with one, `costs` is that constraint's cost). With the
// transitions unit, each policy's last episode is cut at its quota and its
// last row marked as a timeout (D4RL's convention). Fills the attributes
// `policies`, `seed`, `unit`, `count`, `episodes` and the normalisation
// constants of return_ranges over the whole episodes (those not cut; none
// when every episode was cut); the caller adds the rest. Throws
// std::invalid_argument for a count < 1 or bad shares.
OfflineDataset collect_dataset(envs::Env& env, const std::vector<SharedPolicy>& policies, const CollectionPlan& plan,
                               const StepCostSelector& costs = StepCostSelector(),
                               const std::vector<std::string>& constraint_names = {});

}  // namespace bsg::algos
