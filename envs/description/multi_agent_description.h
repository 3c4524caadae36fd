// A multi-agent environment as data (docs/multi_agent.md): the single-agent
// description of one robot (env_description.h), how many robots share the
// arena, how the robots are split into agents, and whether each agent gets
// its own reward and cost or the team's. Built by make_multi_agent
// (envs/multi_agent_env.h), by the same builder that builds every single-agent
// environment; the registered ids are such values (multi_agent_descriptions()).
//
// Parameters (key: default):
//   name                    SafetyBallCircle2-v0   id reported by spec()
//   env                     SafetyBallCircle-v0    one robot's description: agent, task, world,
//                                                  physics and every task parameter
//   bodies                  2                      robots in the arena (1 for a limb split)
//   partition               body                   body: one agent per robot; 2x4 or 4x2: one
//                                                  Ant's legs split into agents (MaMuJoCo's)
//   reward                  own                    own: an agent's robot's task reward; team:
//                                                  every agent gets the team's (the sum)
//   cost                    own                    own: an agent's robot's cost; team: every
//                                                  agent gets the team's (the sum)
//   agent_spacing           1.5 m                  spawn: least planar distance between robots
//   count_agent_collisions  true                   cost_agent_collisions counts (partition body)
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "envs/description/env_description.h"
#include "envs/description/env_parameters.h"

namespace bsg::envs {

struct MultiAgentDescription {
  std::string name = "SafetyBallCircle2-v0";
  EnvDescription env;  // one robot: agent, task, world, physics, task parameters
  int bodies = 2;
  std::string partition = "body";
  std::string reward = "own";
  std::string cost = "own";
  double agent_spacing = 1.5;  // [m] spawn distance between robots' centres, planar
  bool count_agent_collisions = true;

  bool operator==(const MultiAgentDescription&) const = default;
};

// The Ant's legs in the order of its joints (front_left, front_right,
// left_back, right_back; leg l drives joints 2l and 2l+1), grouped into
// agents: "2x4" front and back legs, "4x2" one leg each; empty for "body".
// Throws std::invalid_argument naming an unknown partition.
std::vector<std::vector<int>> ant_leg_groups(const std::string& partition);

// Checks the whole description; throws std::invalid_argument with one line
// naming the key at fault ("multi-agent env: key=value: why").
void check_multi_agent_description(const MultiAgentDescription& description);

// Applies (key, text) overrides: the multi-agent keys above, and every key
// of the robot's description (env_parameters.h) applied to `env`. Throws
// std::invalid_argument with one line naming the key.
MultiAgentDescription apply_multi_agent_overrides(const MultiAgentDescription& base,
                                                  const EnvOverrides& overrides);

// The multi-agent keys and the robot's keys as (key, text) pairs.
EnvOverrides to_multi_agent_overrides(const MultiAgentDescription& description);

// The description as YAML (`bsg envs --describe`): one `key: value  # meaning`
// line per multi-agent key, then the robot's keys as to_yaml() writes them
// (its name aside: the multi-agent name is the robot's).
std::string to_multi_agent_yaml(const MultiAgentDescription& description);

// The registered multi-agent ids (docs/multi_agent.md#ids): several Balls and
// Cars on Circle, the Ant split 2x4 and 4x2 on Run and Circle.
std::vector<MultiAgentDescription> multi_agent_descriptions();

}  // namespace bsg::envs
