#include "envs/description/env_parameters.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <variant>

#include "common/closest_name.h"
#include "common/config_scalar.h"
#include "common/message_text.h"
#include "envs/description/standard_descriptions.h"

namespace bsg::envs {
namespace {

using D = EnvDescription;
using Field = std::variant<bool D::*, int D::*, double D::*, std::string D::*>;

using N = NumericRange;

struct Row {
  EnvParameter info;
  Field field;
};

Row real(std::string_view key, double D::*member, TaskSet tasks, std::string_view unit,
         NumericRange range, std::string_view description) {
  return {{key, ValueType::real, tasks, "", unit, range, {}, description}, member};
}
Row integer(std::string_view key, int D::*member, TaskSet tasks, NumericRange range,
            std::string_view description) {
  return {{key, ValueType::integer, tasks, "", "", range, {}, description}, member};
}
Row boolean(std::string_view key, bool D::*member, TaskSet tasks, std::string_view description) {
  return {{key, ValueType::boolean, tasks, "", "", {}, {}, description}, member};
}
Row choice(std::string_view key, std::string D::*member, TaskSet tasks,
           std::vector<std::string_view> choices, std::string_view description) {
  return {{key, ValueType::choice, tasks, "", "", {}, std::move(choices), description}, member};
}

// clang-format off
const std::vector<Row>& rows() {
  static const std::vector<Row> table = [] {
    std::vector<Row> r = {
      {{"name", ValueType::text, kAllTasks, "", "", {}, {},
        "id reported by spec(), e.g. SafetyBallCircle-v0 or your own name"}, &D::name},
      choice("agent", &D::agent, kAllTasks,
             {"Ball", "Car", "Drone", "Ant"}, "the robot; changing it restarts from the standard description"),
      choice("task", &D::task, kAllTasks,
             {"Circle", "Gather", "Reach", "Run"}, "the task; changing it restarts from the standard description"),
      choice("world", &D::world, kAllTasks,
             {"SmallRoom", "Octagon", "Plane200"},
             "arena: SmallRoom (walls at ±10 m), Octagon (30 m wide), Plane200 (500 m plane)"),
      real("time_step", &D::time_step, kAllTasks, "s", N::above(0),
           "duration of one internal physics step"),
      integer("frame_skip", &D::frame_skip, kAllTasks, N::at_least(1),
              "internal physics steps per environment step (one action is held for all)"),
      integer("max_episode_steps", &D::max_episode_steps, kAllTasks, N::at_least(1),
              "environment steps after which an episode is truncated"),
      real("cost_limit", &D::cost_limit, kAllTasks, "", N::at_least(0),
           "d: limit on the undiscounted episode cost (report Table 3)"),
      boolean("power_upgrade", &D::power_upgrade, kAllTasks,
              "stronger motors for the Car and the Ant (the original's Gather and Reach)"),
      {{"clip_actions", ValueType::boolean, kAllTasks, "Car", "", {}, {},
        "clip the Car's actions to [-1, 1] (the Ball, Drone and Ant always clip)"},
       &D::clip_actions},
      real("circle_radius", &D::circle_radius, kCircle, "m", N::above(0),
           "R: radius of the circle the reward follows"),
      real("circle_x_limit", &D::circle_x_limit, kCircle, "m", N::above(0),
           "cost_outside_bounds when |x| exceeds it"),
      real("circle_spawn_min_radius", &D::circle_spawn_min_radius, kCircle, "m", N::at_least(0),
           "spawn distance from the centre, lower bound"),
      real("circle_spawn_max_radius", &D::circle_spawn_max_radius, kCircle, "m", N::above(0),
           "spawn distance from the centre, upper bound (> circle_spawn_min_radius)"),
      boolean("count_outside_bounds", &D::count_outside_bounds, kCircle | kRun,
              "cost_outside_bounds counts towards the cost"),
      real("placement_half_width", &D::placement_half_width, kGather | kReach, "m", N::above(0),
           "goals and obstacles are drawn in the square [-w, w]²"),
      real("max_altitude", &D::max_altitude, kGather | kReach, "m", N::above(0),
           "cost_out_of_range when the agent's z exceeds it"),
      boolean("count_out_of_range", &D::count_out_of_range, kGather | kReach,
              "cost_out_of_range counts towards the cost"),
      integer("apples", &D::apples, kGather, N::at_least(1), "apples to collect"),
      integer("bombs", &D::bombs, kGather, N::at_least(0), "bombs to avoid"),
      real("gather_detection_distance", &D::gather_detection_distance, kGather, "m", N::above(0),
           "an object is collected closer than this (planar)"),
      real("apple_reward", &D::apple_reward, kGather, "", N::any(), "reward per apple"),
      real("death_reward", &D::death_reward, kGather, "", N::any(),
           "reward of a step in which the agent dies (replaces the step's reward)"),
      real("gather_agent_clearance", &D::gather_agent_clearance, kGather, "m", N::at_least(0),
           "no object is placed closer than this to the agent (planar)"),
      real("gather_spacing", &D::gather_spacing, kGather, "m", N::at_least(0),
           "objects are placed farther apart than this"),
      integer("gather_sensor_bins", &D::gather_sensor_bins, kGather, N::at_least(1),
              "bins of each of the two pseudo-LIDARs (apples, bombs)"),
      real("gather_sensor_range", &D::gather_sensor_range, kGather, "m", N::above(0),
           "range of the two pseudo-LIDARs"),
      boolean("count_gathered_bombs", &D::count_gathered_bombs, kGather,
              "cost_gathered_bombs counts towards the cost"),
      real("goal_radius", &D::goal_radius, kReach, "m", N::above(0),
           "the goal is reached closer than this (planar)"),
      real("goal_bonus", &D::goal_bonus, kReach, "", N::any(), "reward for reaching the goal"),
      real("goal_max_speed", &D::goal_max_speed, kReach, "m/s", N::above(0),
           "a goal counts only below this 3-d speed"),
      real("goal_respawn_clearance", &D::goal_respawn_clearance, kReach, "m", N::at_least(0),
           "a new goal is drawn farther than this from agent, Box and zones"),
      real("reach_spacing", &D::reach_spacing, kReach, "m", N::at_least(0),
           "placement clearance: agent-goal, agent-obstacle, obstacle-obstacle and obstacle-goal"),
      real("reach_reward_scale", &D::reach_reward_scale, kReach, "", N::any(),
           "factor on the progress term d_prev - d"),
      choice("goal_scheme", &D::goal_scheme, kReach, {"random", "corners"},
             "random: drawn in the room; corners: alternates (-6, 6) and (6, 6) (the fork)"),
      integer("zones", &D::zones, kReach, N::at_least(0), "puddles or pillars"),
      choice("zone_type", &D::zone_type, kReach, {"puddle", "pillar"},
             "puddle (radius 1 m) or pillar (radius 0.45 m); sets zone_radius"),
      choice("zone_layout", &D::zone_layout, kReach, {"random", "barrier"},
             "random: zones drawn at every reset; barrier: the fork's CarReach map of 17 fixed "
             "puddles with the spawn at (-6, 6) (needs zones: 17)"),
      choice("obstacle_clearance_from", &D::obstacle_clearance_from, kReach, {"spawn", "stale"},
             "spawn: Box and zones keep reach_spacing from this episode's spawn and drawn goal; "
             "stale: from the agent's and goal's poses before the reset moved them (the fork)"),
      real("zone_radius", &D::zone_radius, kReach, "m", N::above(0),
           "a zone costs when the agent's disc overlaps it"),
      boolean("box", &D::box, kReach, "the moving Box (a collision obstacle)"),
      real("box_circle_radius", &D::box_circle_radius, kReach, "m", N::at_least(0),
           "radius of the circle the Box's pivot follows"),
      integer("lidar_rays", &D::lidar_rays, kReach, N::at_least(0), "rays of the LIDAR (0: no LIDAR)"),
      real("lidar_range", &D::lidar_range, kReach, "m", N::above(0), "range of the LIDAR"),
      integer("reach_sensor_bins", &D::reach_sensor_bins, kReach, N::at_least(0),
              "bins of the pseudo-LIDAR over the zones (0: none)"),
      real("reach_sensor_range", &D::reach_sensor_range, kReach, "m", N::above(0),
           "range of the pseudo-LIDAR over the zones"),
      boolean("count_collisions", &D::count_collisions, kReach,
              "cost_collisions counts towards the cost"),
      real("run_y_limit", &D::run_y_limit, kRun, "m", N::above(0),
           "avenue half-width: cost_outside_bounds when |y| exceeds it"),
      real("run_speed_limit", &D::run_speed_limit, kRun, "m/s", N::above(0),
           "cost_velocity_violation above this planar speed"),
      real("run_spawn_range", &D::run_spawn_range, kRun, "m", N::at_least(0),
           "spawn x and y are drawn in [-range, range]"),
      boolean("count_velocity_violation", &D::count_velocity_violation, kRun,
              "cost_velocity_violation counts towards the cost"),
    };
    return r;
  }();
  return table;
}
// clang-format on

const Row& row_of(const EnvParameter& parameter) {
  if (const Row* row = find_row(rows(), parameter.key)) return *row;
  throw std::logic_error("internal: '" + std::string(parameter.key) + "' is not an env parameter");
}

[[noreturn]] void fail(const std::string& key, const std::string& value, const std::string& why) {
  throw std::invalid_argument("env: " + key + "=" + value + ": " + why);
}

std::string task_names(TaskSet tasks) {
  std::vector<std::string_view> names;
  const std::array<std::pair<TaskSet, std::string_view>, 4> all = {
      {{kCircle, "Circle"}, {kGather, "Gather"}, {kReach, "Reach"}, {kRun, "Run"}}};
  for (const auto& [bit, name] : all) {
    if ((tasks & bit) != 0) names.push_back(name);
  }
  return comma_separated(names);
}

TaskSet task_bit(const std::string& task) {
  if (task == "Circle") return kCircle;
  if (task == "Gather") return kGather;
  if (task == "Reach") return kReach;
  if (task == "Run") return kRun;
  return 0;
}

constexpr std::string_view expected_text(ValueType type) {
  switch (type) {
    case ValueType::boolean: return "expects true or false";
    case ValueType::integer: return "expects an integer";
    case ValueType::real: return "expects a finite real number";
    default: return "expects non-empty text";
  }
}

// Parses `text` into the field of `row` through the shared parser
// (common/parameter_table.h); fails naming key and value.
void set_value(EnvDescription& d, const Row& row, const std::string& text) {
  const std::string key(row.info.key);
  std::visit(
      [&](auto member) {
        auto value = d.*member;
        switch (parse_scalar(text, row.info.range, value)) {
          case ScalarProblem::none: break;
          case ScalarProblem::not_a_value: fail(key, text, std::string(expected_text(row.info.type)));
          case ScalarProblem::out_of_range: fail(key, text, "must be " + row.info.valid_text());
        }
        if constexpr (std::is_same_v<decltype(value), std::string>) {
          // A name is an id: it goes into YAML, logs and directory names unquoted.
          const bool id_like = std::all_of(text.begin(), text.end(), [](char c) {
            return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '-' || c == '_' || c == '.';
          });
          const auto& choices = row.info.choices;
          if (choices.empty() && !id_like) fail(key, text, "use letters, digits, '-', '_' and '.' only");
          if (!choices.empty() && std::find(choices.begin(), choices.end(), text) == choices.end()) {
            const std::string guess = closest_name(text, choices);
            fail(key, text, "unknown " + key + (guess.empty() ? "" : " (did you mean " + guess + "?)") +
                                "; valid: " + comma_separated(choices));
          }
        }
        d.*member = std::move(value);
      },
      row.field);
}

const Row& row_named(const std::string& key, const std::string& value) {
  if (const Row* row = find_row(rows(), key)) return *row;
  const std::string guess = closest_row_key(rows(), key);
  fail(key, value, "unknown parameter" + (guess.empty() ? std::string() : " (did you mean " + guess + "?)") +
                       "; `bsg envs --describe ID` lists the parameters of an environment");
}

// Random sequential placement of equal discs jams near 54.7 % of the plane
// covered (Feder 1980; Hinrichsen, Feder and Jøssang 1986): more discs than
// that never finish, so they are refused before the first draw.
constexpr double kJammingCoverage = 0.547;

// How many discs of diameter `spacing` can be placed at random in the square
// of half-width `half_width` (their centres inside it) before jamming.
double placeable(double half_width, double spacing) {
  if (spacing <= 0) return INFINITY;
  const double side = 2 * half_width + spacing;  // discs may overhang by spacing/2
  return kJammingCoverage * side * side / (std::numbers::pi * spacing * spacing / 4);
}

// `what` names the counted keys, e.g. "apples + bombs"; `spacing_key` the clearance.
void check_placement(const EnvDescription& d, const std::string& what, int count,
                     const std::string& spacing_key, double spacing) {
  const double limit = placeable(d.placement_half_width, spacing);
  if (count > limit) {
    fail(what, std::to_string(count),
         "cannot place " + std::to_string(count) + " objects " + spacing_key + "=" +
             format_config_real(spacing) + " m apart in the square of placement_half_width=" +
             format_config_real(d.placement_half_width) + " m (random placement jams beyond about " +
             std::to_string(static_cast<long>(limit)) + ")");
  }
}

}  // namespace

const std::vector<EnvParameter>& env_parameters() {
  static const std::vector<EnvParameter> parameters = [] {
    std::vector<EnvParameter> list;
    for (const Row& row : rows()) list.push_back(row.info);
    return list;
  }();
  return parameters;
}

const EnvParameter* find_env_parameter(std::string_view key) {
  const Row* row = find_row(rows(), key);
  return row != nullptr ? &row->info : nullptr;
}

std::string env_parameter_text(const EnvDescription& d, const EnvParameter& parameter) {
  return std::visit([&](auto member) { return scalar_text(d.*member); }, row_of(parameter).field);
}

std::string EnvParameter::valid_text() const {
  switch (type) {
    case ValueType::boolean: return "true or false";
    case ValueType::integer:
    case ValueType::real: return range.inequality_text();
    case ValueType::choice: return comma_separated(choices);
    default: return "letters, digits, -, _, .";
  }
}

bool applies_to(const EnvParameter& parameter, const EnvDescription& description) {
  return (parameter.tasks & task_bit(description.task)) != 0 &&
         (parameter.agent.empty() || parameter.agent == description.agent);
}

void check_env_description(const EnvDescription& d) {
  for (const Row& row : rows()) {
    // Every value passes its own key's check (a description built in code too).
    EnvDescription copy = d;
    set_value(copy, row, env_parameter_text(d, row.info));
  }
  if (task_bit(d.task) == kCircle && d.circle_spawn_min_radius >= d.circle_spawn_max_radius) {
    fail("circle_spawn_min_radius", format_config_real(d.circle_spawn_min_radius),
         "must be below circle_spawn_max_radius=" + format_config_real(d.circle_spawn_max_radius));
  }
  if (task_bit(d.task) == kGather) {
    check_placement(d, "apples + bombs", d.apples + d.bombs, "gather_spacing", d.gather_spacing);
  }
  if (task_bit(d.task) == kReach) {
    // The goal, the Box and the zones keep reach_spacing from each other.
    check_placement(d, d.box ? "goal + box + zones" : "goal + zones", 1 + (d.box ? 1 : 0) + d.zones,
                    "reach_spacing", d.reach_spacing);
    if (d.zone_layout == "barrier" && d.zones != static_cast<int>(kBarrierZones.size())) {
      fail("zones", std::to_string(d.zones),
           "zone_layout barrier places exactly " + std::to_string(kBarrierZones.size()) + " zones");
    }
    if (d.goal_scheme == "corners" && d.placement_half_width < 6) {
      fail("placement_half_width", format_config_real(d.placement_half_width),
           "goal_scheme corners puts goals at (±6, 6): needs placement_half_width >= 6");
    }
  }
}

EnvDescription apply_env_overrides(const EnvDescription& base, const EnvOverrides& overrides) {
  EnvDescription d = base;
  // Agent and task first: they choose the standard description the rest amends.
  std::string agent = base.agent, task = base.task;
  bool combination_changed = false;
  for (const auto& [key, value] : overrides) {
    const Row& row = row_named(key, value);
    if (key == "agent" || key == "task") {
      EnvDescription probe = d;
      set_value(probe, row, value);
      (key == "agent" ? agent : task) = value;
      combination_changed = combination_changed || value != (key == "agent" ? base.agent : base.task);
    }
  }
  if (combination_changed) d = standard_description(agent, task);
  bool radius_given = false;
  for (const auto& [key, value] : overrides) radius_given = radius_given || key == "zone_radius";
  for (const auto& [key, value] : overrides) {
    const Row& row = row_named(key, value);
    if (key == "agent" || key == "task") continue;
    if (!applies_to(row.info, d)) {
      const std::string who = row.info.agent.empty()
                                  ? "the " + d.task + " task has no such parameter (it belongs to " +
                                        task_names(row.info.tasks) + ")"
                                  : "only the " + std::string(row.info.agent) + " has it, not the " + d.agent;
      fail(key, value, who);
    }
    set_value(d, row, value);
    if (key == "zone_type" && !radius_given) d.zone_radius = standard_zone_radius(d.zone_type);
  }
  check_env_description(d);
  return d;
}

EnvOverrides to_env_overrides(const EnvDescription& d) {
  EnvOverrides list;
  for (const EnvParameter& parameter : env_parameters()) {
    if (applies_to(parameter, d)) list.emplace_back(parameter.key, env_parameter_text(d, parameter));
  }
  return list;
}

std::string to_yaml(const EnvDescription& d) {
  std::ostringstream out;
  for (const EnvParameter& parameter : env_parameters()) {
    if (!applies_to(parameter, d)) continue;
    std::string value = env_parameter_text(d, parameter);
    out << parameter.key << ": " << value << "  # " << parameter.description;
    if (!parameter.unit.empty()) out << " [" << parameter.unit << "]";
    out << "\n";
  }
  return out.str();
}

}  // namespace bsg::envs
