// A policy that `bsg collect` rolls out (docs/datasets.md#collecting): the
// random policy, or the policy of a run's checkpoint (checkpoint_policy.h).
// Each episode restarts the policy's own random stream from a seed of its own,
// so that any episode of a collection can be replayed alone.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>

namespace bsg::algos {

class CollectionPolicy {
 public:
  virtual ~CollectionPolicy() = default;
  // One line for the file's attributes, e.g. "random" or "checkpoint runs/x (epoch 50 of 50, sampled)".
  virtual std::string description() const = 0;
  // Restarts the policy's random stream at the start of an episode.
  virtual void start_episode(std::uint64_t seed) = 0;
  // The action for `observation` (the environment's raw observation).
  virtual void act(std::span<const double> observation, std::span<double> action) = 0;
};

// Actions drawn uniformly in [low, high] in every dimension.
std::unique_ptr<CollectionPolicy> make_random_policy(int action_dim, double low, double high);

}  // namespace bsg::algos
