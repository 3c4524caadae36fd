// Assembles an environment from its description (design.md, the report's
// EnvironmentBuilder): the world (layout, time step and sub-steps), the agent
// built in it with the description's power and clipping settings, then the
// task reading its counts, sizes and ranges from the same description. Every
// environment, standard or custom, is built here.
#pragma once

#include <memory>
#include <string>

#include "envs/agents/agent.h"
#include "envs/env.h"
#include "envs/multi_agent_env.h"
#include "envs/description/env_description.h"
#include "envs/physics/world.h"

namespace bsg::envs {

// Every agent file exposes one of these, e.g. make_ball_agent (ball_agent.h).
using AgentFactory = std::unique_ptr<Agent> (*)(World& world, const AgentOptions& options);

// True for the agents whose factory builds a lean model (the Car and the Ant).
bool agent_has_lean_model(const std::string& agent);

// "SmallRoom", "Octagon" or "Plane200"; throws std::invalid_argument otherwise.
WorldLayout parse_world_layout(const std::string& world);

// Checks the description (env_parameters.h) and builds it. Throws
// std::invalid_argument naming the key at fault, or the agent if options ask
// for a lean model it does not have.
std::unique_ptr<Env> build_env(const EnvDescription& description, const EnvOptions& options);

// Checks a multi-agent description and builds it: a limb split over the
// single-agent environment built above, or several robots in one world.
// Throws std::invalid_argument with one line naming the key at fault.
std::unique_ptr<MultiAgentEnv> build_multi_agent_env(const MultiAgentDescription& description,
                                                     const EnvOptions& options);

}  // namespace bsg::envs
