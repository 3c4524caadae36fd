#include "registry.h"

#include <stdexcept>

#include "ant_agent.h"
#include "ball_agent.h"
#include "car_agent.h"
#include "circle_task.h"
#include "drone_agent.h"
#include "gather_task.h"
#include "reach_task.h"
#include "run_task.h"

namespace bsg::envs {

void add_agent(std::map<std::string, EnvRegistration>& entries, const std::string& agent_name,
               AgentFactory make_agent, int max_episode_steps, const TaskCostLimits& cost_limits,
               LeanModel lean_model, ZoneKind reach_zones) {
  const std::pair<TaskBlueprint, double> tasks[] = {
      {circle_task(), cost_limits.circle},
      {gather_task(), cost_limits.gather},
      {reach_task(reach_zones), cost_limits.reach},
      {run_task(), cost_limits.run},
  };
  for (const auto& [blueprint, cost_limit] : tasks) {
    const std::string id = "Safety" + agent_name + blueprint.name + "-v0";
    if (entries.contains(id)) throw std::logic_error("environment registered twice: " + id);
    entries.emplace(id, EnvRegistration{id, agent_name, make_agent, blueprint, max_episode_steps,
                                        cost_limit, lean_model == LeanModel::kBuilt});
  }
}

const std::map<std::string, EnvRegistration>& registry() {
  static const std::map<std::string, EnvRegistration> entries = [] {
    std::map<std::string, EnvRegistration> result;
    // Episode lengths and cost limits: docs/environments.md#the-sixteen-environments (report Table 3).
    // Lean models (env.h): the Ball is one sphere, nothing to weld; the Car
    // welds its sensor links into the chassis (car_agent.h); the Drone has
    // none yet.
    add_agent(result, "Ball", make_ball_agent, 250, kStandardCostLimits, LeanModel::kNone);
    add_agent(result, "Car", make_car_agent, 500, kStandardCostLimits, LeanModel::kBuilt);
    add_agent(result, "Drone", make_drone_agent, 500, kStandardCostLimits, LeanModel::kNone,
              ZoneKind::kPillar);
    add_agent(result, "Ant", make_ant_agent, 1000, TaskCostLimits{.reach = 25},
              LeanModel::kBuilt);
    return result;
  }();
  return entries;
}

const EnvRegistration& find_registration(const std::string& id) {
  const auto& entries = registry();
  const auto found = entries.find(id);
  if (found == entries.end()) {
    std::string valid;
    for (const auto& [name, entry] : entries) valid += (valid.empty() ? "" : ", ") + name;
    throw std::invalid_argument("unknown environment id '" + id + "'; valid ids: " + valid);
  }
  return found->second;
}

std::unique_ptr<Env> make(const std::string& id, const EnvOptions& options) {
  return build_env(find_registration(id), options);
}

bool has_lean_model(const std::string& id) { return find_registration(id).has_lean_model; }

std::vector<std::string> registered_ids() {
  std::vector<std::string> ids;
  for (const auto& [id, entry] : registry()) ids.push_back(id);
  return ids;
}

}  // namespace bsg::envs
