#include "envs/description/multi_agent_description.h"

#include <algorithm>
#include <array>
#include <sstream>
#include <stdexcept>
#include <string_view>

#include "common/closest_name.h"
#include "common/config_scalar.h"
#include "envs/description/standard_descriptions.h"

namespace bsg::envs {
namespace {

constexpr int kMaxBodies = 8;
// Random sequential placement of equal discs jams near 54.7 % of the area
// covered (as env_parameters.cpp's check of Reach's counts).
constexpr double kJammingCoverage = 0.547;
constexpr std::array<std::string_view, 7> kKeys = {
    "name", "bodies", "partition", "reward", "cost", "agent_spacing", "count_agent_collisions"};

[[noreturn]] void fail(std::string_view key, const std::string& value, const std::string& why) {
  throw std::invalid_argument("multi-agent env: " + std::string(key) + "=" + value + ": " + why);
}

void require_choice(std::string_view key, const std::string& value,
                    std::initializer_list<std::string_view> choices) {
  std::string valid;
  for (const std::string_view choice : choices) {
    if (value == choice) return;
    valid += (valid.empty() ? "" : ", ") + std::string(choice);
  }
  fail(key, value, "not one of " + valid);
}

MultiAgentDescription split_ant(const std::string& task, const std::string& partition) {
  MultiAgentDescription d;
  d.env = standard_description("Ant", task);
  d.name = "SafetyAnt" + task + partition + "-v0";
  d.env.name = d.name;
  d.bodies = 1;
  d.partition = partition;
  d.reward = "team";  // one robot, one reward and one cost, shared by its limbs
  d.cost = "team";
  return d;
}

MultiAgentDescription several(const std::string& agent, const std::string& task, int bodies) {
  MultiAgentDescription d;
  d.env = standard_description(agent, task);
  d.name = "Safety" + agent + task + std::to_string(bodies) + "-v0";
  d.env.name = d.name;
  d.bodies = bodies;
  return d;
}

void set_key(MultiAgentDescription& d, const std::string& key, const std::string& value) {
  if (key == "name") {
    if (value.empty()) fail(key, value, "must not be empty");
    d.name = value;
    d.env.name = value;
  } else if (key == "bodies") {
    const auto parsed = parse_config_integer(value);
    if (!parsed) fail(key, value, "not an integer");
    if (*parsed < 1 || *parsed > kMaxBodies) fail(key, value, "must be in [1, 8]");
    d.bodies = static_cast<int>(*parsed);
  } else if (key == "partition") {
    d.partition = value;
  } else if (key == "reward") {
    d.reward = value;
  } else if (key == "cost") {
    d.cost = value;
  } else if (key == "agent_spacing") {
    const auto parsed = parse_config_real(value);
    if (!parsed) fail(key, value, "not a finite real");
    d.agent_spacing = *parsed;
  } else {  // count_agent_collisions
    const auto parsed = parse_config_bool(value);
    if (!parsed) fail(key, value, "not a boolean (true or false)");
    d.count_agent_collisions = *parsed;
  }
}

}  // namespace

std::vector<std::vector<int>> ant_leg_groups(const std::string& partition) {
  if (partition == "body") return {};
  if (partition == "2x4") return {{0, 1}, {2, 3}};  // front legs, back legs
  if (partition == "4x2") return {{0}, {1}, {2}, {3}};
  fail("partition", partition, "not one of body, 2x4, 4x2");
}

void check_multi_agent_description(const MultiAgentDescription& d) {
  check_env_description(d.env);
  if (d.name.empty()) fail("name", d.name, "must not be empty");
  if (d.bodies < 1 || d.bodies > kMaxBodies) fail("bodies", std::to_string(d.bodies), "must be in [1, 8]");
  require_choice("partition", d.partition, {"body", "2x4", "4x2"});
  require_choice("reward", d.reward, {"own", "team"});
  require_choice("cost", d.cost, {"own", "team"});
  if (!(d.agent_spacing > 0)) fail("agent_spacing", format_config_real(d.agent_spacing), "must be > 0");
  if (d.partition != "body") {
    if (d.env.agent != "Ant") {
      fail("partition", d.partition, "splits the Ant's legs; the " + d.env.agent + " has none (use body)");
    }
    if (d.bodies != 1) fail("bodies", std::to_string(d.bodies), "a limb split has one robot (bodies=1)");
    if (d.reward != "team") fail("reward", d.reward, "the limbs of one robot share its reward (team)");
    if (d.cost != "team") fail("cost", d.cost, "the limbs of one robot share its cost (team)");
    return;
  }
  if (d.bodies < 2) fail("bodies", std::to_string(d.bodies), "partition body needs at least 2 robots");
  if (d.env.task != "Circle" && d.env.task != "Reach") {
    fail("task", d.env.task, "several robots share an arena on Circle and Reach only so far");
  }
  // Reach (MultiGoal): the placement sampler's attempt guard refuses what does not fit.
  if (d.env.task == "Reach") return;
  // The robots' spawn discs must fit the Circle's spawn annulus.
  const double r_min = d.env.circle_spawn_min_radius, r_max = d.env.circle_spawn_max_radius;
  const double discs = d.bodies * 0.25 * d.agent_spacing * d.agent_spacing;
  if (discs > kJammingCoverage * (r_max * r_max - r_min * r_min)) {
    fail("agent_spacing", format_config_real(d.agent_spacing),
         std::to_string(d.bodies) + " robots this far apart do not fit the spawn annulus " +
             format_config_real(r_min) + " m .. " + format_config_real(r_max) + " m");
  }
}

MultiAgentDescription apply_multi_agent_overrides(const MultiAgentDescription& base,
                                                  const EnvOverrides& overrides) {
  MultiAgentDescription d = base;
  EnvOverrides robot;
  for (const auto& [key, value] : overrides) {
    if (std::find(kKeys.begin(), kKeys.end(), key) != kKeys.end()) {
      set_key(d, key, value);
    } else if (find_env_parameter(key) != nullptr) {
      robot.emplace_back(key, value);
    } else {
      std::vector<std::string_view> candidates(kKeys.begin(), kKeys.end());
      for (const EnvParameter& parameter : env_parameters()) candidates.push_back(parameter.key);
      const std::string guess = closest_name(key, candidates);
      fail(key, value, "unknown parameter" + (guess.empty() ? std::string() : " (did you mean " + guess + "?)"));
    }
  }
  if (!robot.empty()) {
    d.env = apply_env_overrides(d.env, robot);
    d.env.name = d.name;
  }
  check_multi_agent_description(d);
  return d;
}

EnvOverrides to_multi_agent_overrides(const MultiAgentDescription& d) {
  EnvOverrides list = {{"name", d.name},
                       {"bodies", std::to_string(d.bodies)},
                       {"partition", d.partition},
                       {"reward", d.reward},
                       {"cost", d.cost},
                       {"agent_spacing", format_config_real(d.agent_spacing)},
                       {"count_agent_collisions", d.count_agent_collisions ? "true" : "false"}};
  for (auto& entry : to_env_overrides(d.env)) {
    if (entry.first != "name") list.push_back(std::move(entry));
  }
  return list;
}

std::string to_multi_agent_yaml(const MultiAgentDescription& d) {
  // The meanings of kKeys, in its order (docs/multi_agent.md#descriptions).
  constexpr std::array<std::string_view, kKeys.size()> kMeanings = {
      "id reported by the spec",
      "robots in the arena",
      "body: one agent per robot; 2x4, 4x2: the Ant's legs split into agents",
      "own: each agent its robot's task reward; team: every agent the sum",
      "own: each agent its robot's cost; team: every agent the sum",
      "least planar distance between robots' centres at spawn [m]",
      "whether cost_agent_collisions counts in the cost"};
  const EnvOverrides pairs = to_multi_agent_overrides(d);
  std::ostringstream out;
  for (size_t k = 0; k < kKeys.size(); ++k) {
    out << pairs[k].first << ": " << pairs[k].second << "  # " << kMeanings[k] << "\n";
  }
  std::istringstream robot(to_yaml(d.env));
  for (std::string line; std::getline(robot, line);) {
    if (!line.starts_with("name: ")) out << line << "\n";
  }
  return out.str();
}

std::vector<MultiAgentDescription> multi_agent_descriptions() {
  return {several("Ball", "Circle", 2), several("Ball", "Circle", 3), several("Car", "Circle", 2),
          several("Ball", "Reach", 2), several("Car", "Reach", 2),
          split_ant("Run", "2x4"), split_ant("Run", "4x2"),
          split_ant("Circle", "2x4"), split_ant("Circle", "4x2")};
}

}  // namespace bsg::envs
