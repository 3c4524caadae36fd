// The off-policy learner of a run's algorithm: sac and sac-lag give a SacLearner, td3 and td3-lag a
// Td3Learner, ddpg and ddpg-lag a DdpgLearner (the -lag forms are the same learners with a cost
// critic per constraint; their multipliers are the trainer's). To add a learner, see
// docs/architecture.md#adding-an-off-policy-algorithm.
#pragma once

#include <memory>

#include "algos/off_policy/off_policy_learner.h"
#include "common/random.h"
#include "common/run_config.h"

namespace bsg::algos {

// Networks drawn from `init_rng` (the actor, each reward critic, each cost critic); cost_count = 0
// for the unconstrained algorithms. Throws std::invalid_argument naming the algorithm if
// config.alg is not off-policy.
std::unique_ptr<OffPolicyLearner> make_off_policy_learner(const RunConfig& config, int observation_size,
                                                          int action_size, int cost_count, Rng& init_rng);

}  // namespace bsg::algos
