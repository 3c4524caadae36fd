// How any family's trained policy acts (design.md "Families and the run skeleton"): from the
// environment's raw observation to an action, the family's observation normaliser inside. One
// interface below the families serves the final evaluation of training, `bsg eval`, `bsg collect`
// and anything later (load_policy.h reads one from a run directory).
#pragma once

#include <span>

#include "common/random.h"

namespace bsg::algos {

// Mean: the policy's mean action (the on-policy Gaussian's mu, the off-policy actor's
// tanh(mu)), as the report evaluates. Sampled: the action the policy explores with (mu + sigma eps
// at the policy's sigma; SAC's squashed sample; TD3's and DDPG's Gaussian noise), drawn from `noise`.
enum class ActionMode { mean, sampled };

class ActingPolicy {
 public:
  virtual ~ActingPolicy() = default;
  virtual int observation_size() const = 0;
  virtual int action_size() const = 0;
  // Writes the action for `observation` (the environment's raw one); a mean action draws
  // nothing from `noise`. Throws std::invalid_argument if the sizes differ from the policy's.
  virtual void act(std::span<const double> observation, ActionMode mode, Rng& noise, std::span<double> action) = 0;
};

// Throws std::invalid_argument naming `who` and both sizes unless the observation and action have
// the policy's sizes.
void check_acting_sizes(const ActingPolicy& policy, std::span<const double> observation, std::span<double> action,
                        const char* who);

}  // namespace bsg::algos
