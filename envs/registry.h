// The registry of environment ids (design.md; OpenSpiel-style function-local
// static map). make() and registered_ids() of env.h read it.
//
// Registering an agent on all four tasks is one line in registry.cpp:
//   add_agent(entries, "Car", make_car_agent, 500, kStandardCostLimits);
// which registers SafetyCarCircle-v0, SafetyCarGather-v0, SafetyCarReach-v0
// and SafetyCarRun-v0. The Drone's Reach uses pillars:
//   add_agent(entries, "Drone", make_drone_agent, 500, kStandardCostLimits, ZoneKind::kPillar);
// A new task is one more line in add_agent().
#pragma once

#include <map>
#include <string>

#include "env_builder.h"
#include "zone_obstacles.h"

namespace bsg::envs {

// Cost limits d per task from the report's Table 3 (docs/environments.md#the-sixteen-environments).
struct TaskCostLimits {
  double circle = 25;
  double gather = 0.2;
  double reach = 10;
  double run = 25;
};

// Ball, Car and Drone; the Ant's Reach limit is 25 instead of 10.
inline constexpr TaskCostLimits kStandardCostLimits{};

// Registers Safety<agent_name><Task>-v0 for every task. Reach uses puddles,
// or pillars for a flying agent (the Drone, docs/environments.md#the-sixteen-environments).
void add_agent(std::map<std::string, EnvRegistration>& entries, const std::string& agent_name,
               AgentFactory make_agent, int max_episode_steps, const TaskCostLimits& cost_limits,
               ZoneKind reach_zones = ZoneKind::kPuddle);

// Every registered id, built once on first use.
const std::map<std::string, EnvRegistration>& registry();

// The entry for `id`; throws std::invalid_argument listing the valid ids.
const EnvRegistration& find_registration(const std::string& id);

}  // namespace bsg::envs
