// A multi-agent environment seen as one agent (docs/multi_agent.md#one-learner-for-the-whole-team):
// the baseline of Gu et al. 2021 and SafePO, where a single-agent learner controls every agent
// jointly. Its observation is the agents' observations one after the other, its action every
// agent's action in agent order, and its reward and cost the agents' means, so that an episode's
// return and cost are what the multi-agent learners report (the agents' mean of their own sums)
// and d is the same limit per agent. A team reward or cost (the split Ant) is every agent's, so
// its mean is the team's own value.
//
// A joint environment has one layout and one state only when it holds one robot (the split Ant);
// with several robots reset_to, layout, state and teleport_agent throw std::logic_error naming
// the multi-agent face to use instead.
#pragma once

#include <memory>

#include "envs/env.h"
#include "envs/multi_agent_env.h"

namespace bsg::envs {

// Throws std::invalid_argument if `team` is null.
std::unique_ptr<Env> make_joint_control(std::unique_ptr<MultiAgentEnv> team);

}  // namespace bsg::envs
