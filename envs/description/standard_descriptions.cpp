#include "envs/description/standard_descriptions.h"

#include <array>
#include <stdexcept>
#include <string_view>

namespace bsg::envs {
namespace {

// Per agent: episode length (report Table 3), Run speed limit, Reach zones.
struct AgentRow {
  std::string_view agent;
  int max_episode_steps;
  double run_speed_limit;  // [m/s] the agent's velocity limit (docs/environments.md#run)
  std::string_view reach_zone_type;
  double reach_cost_limit;  // the Ant's Reach limit is 25 (report Table 3)
};

constexpr std::array<AgentRow, 4> kAgents = {{
    {"Ball", 250, 2.5, "puddle", 10},
    {"Car", 500, 1.5, "puddle", 10},
    {"Drone", 500, 1.5, "pillar", 10},
    {"Ant", 1000, 1.5, "puddle", 25},
}};

// Per task: world, physics (docs/environments.md#physics-settings), cost limit, power.
struct TaskRow {
  std::string_view task;
  std::string_view world;
  double time_step;  // [s]
  int frame_skip;
  double cost_limit;
  bool power_upgrade;  // docs/environments.md#agents "power upgrade"
};

constexpr std::array<TaskRow, 4> kTasks = {{
    {"Circle", "Octagon", 1.0 / 240.0, 4, 25, false},
    {"Gather", "SmallRoom", 1.0 / 240.0, 4, 0.2, true},
    {"Reach", "SmallRoom", 1.0 / 60.0, 1, 10, true},
    {"Run", "Plane200", 1.0 / 240.0, 4, 25, false},
}};

std::string valid_names(const auto& rows, auto field) {
  std::string names;
  for (const auto& row : rows) names += (names.empty() ? "" : ", ") + std::string(row.*field);
  return names;
}

}  // namespace

double standard_zone_radius(const std::string& zone_type) { return zone_type == "pillar" ? 0.45 : 1.0; }

EnvDescription standard_description(const std::string& agent, const std::string& task) {
  const AgentRow* a = nullptr;
  for (const AgentRow& row : kAgents) a = row.agent == agent ? &row : a;
  if (a == nullptr) {
    throw std::invalid_argument("env: agent=" + agent + ": unknown agent; valid: " +
                                valid_names(kAgents, &AgentRow::agent));
  }
  const TaskRow* t = nullptr;
  for (const TaskRow& row : kTasks) t = row.task == task ? &row : t;
  if (t == nullptr) {
    throw std::invalid_argument("env: task=" + task + ": unknown task; valid: " +
                                valid_names(kTasks, &TaskRow::task));
  }
  EnvDescription d;
  d.name = "Safety" + agent + task + "-v0";
  d.agent = agent;
  d.task = task;
  d.world = std::string(t->world);
  d.time_step = t->time_step;
  d.frame_skip = t->frame_skip;
  d.max_episode_steps = a->max_episode_steps;
  d.cost_limit = task == "Reach" ? a->reach_cost_limit : t->cost_limit;
  d.power_upgrade = t->power_upgrade;
  d.run_speed_limit = a->run_speed_limit;
  d.zone_type = std::string(a->reach_zone_type);
  d.zone_radius = standard_zone_radius(d.zone_type);
  return d;
}

std::vector<EnvDescription> standard_descriptions() {
  std::vector<EnvDescription> list;
  for (const AgentRow& a : kAgents) {
    for (const TaskRow& t : kTasks) list.push_back(standard_description(std::string(a.agent), std::string(t.task)));
  }
  return list;
}

}  // namespace bsg::envs
