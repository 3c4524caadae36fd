// Assembles an environment from its parts (design.md, the report's
// EnvironmentBuilder): the task's world (layout and sub-steps), the agent
// built in it with the task's power setting, then the task itself.
#pragma once

#include <memory>
#include <string>

#include "agent.h"
#include "env.h"
#include "task.h"

namespace bsg::envs {

// Every agent file exposes one of these, e.g. make_ball_agent (ball_agent.h).
using AgentFactory = std::unique_ptr<Agent> (*)(World& world, const AgentOptions& options);

// One registry entry: everything needed to build an id (docs/environments.md#the-sixteen-environments).
struct EnvRegistration {
  std::string id;           // "Safety<Agent><Task>-v0"
  std::string agent_name;   // "Ball", "Car", "Drone", "Ant"
  AgentFactory make_agent = nullptr;
  TaskBlueprint task;
  int max_episode_steps = 0;
  double cost_limit = 0;    // report Table 3
};

std::unique_ptr<Env> build_env(const EnvRegistration& registration, const EnvOptions& options);

}  // namespace bsg::envs
