#include "envs/tasks/reach_task.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "envs/tasks/layout_checks.h"
#include "envs/physics/orientation.h"
#include "envs/tasks/placement_sampler.h"

namespace bsg::envs {

namespace {

ZoneKind zone_kind(const std::string& zone_type) {
  return zone_type == "pillar" ? ZoneKind::kPillar : ZoneKind::kPuddle;
}

}  // namespace

ReachTask::ReachTask(World& world, Agent& agent, const EnvDescription& description,
                     BoxClock box_clock, const ReachTask* hazards)
    : world_(world),
      agent_(agent),
      description_(description),
      box_clock_(box_clock),
      zones_(zone_kind(description.zone_type), description.zones, description.zone_radius),
      hazards_(hazards) {
  if (hazards != nullptr && (description.zones != 0 || description.box)) {
    throw std::invalid_argument("Reach: a task sharing another's hazards has no zones or Box of its own");
  }
  if (description.lidar_rays > 0) lidar_.emplace(world, description.lidar_rays, description.lidar_range);
  if (description.reach_sensor_bins > 0) {
    pseudo_lidar_.emplace(description.reach_sensor_bins, description.reach_sensor_range);
  }
  if (description.box) box_.emplace(world, description.box_circle_radius);
  // Before the first reset the agent stands where it was built and the goal
  // zone at the origin.
  stale_agent_ = agent.traits().initial_position;
}

btVector3 ReachTask::next_corner() {
  const btVector3 corner(corner_flag_ ? 6.0 : -6.0, 6.0, 0.0);
  corner_flag_ = !corner_flag_;
  return corner;
}

void ReachTask::sample_layout(Rng& rng, Layout& layout) {
  constexpr double kPi = std::numbers::pi;
  const double half_width = description_.placement_half_width;
  const double spacing = description_.reach_spacing;
  if (box_ && !box_constants_drawn_) {
    box_spawn_orientation_ = quaternion_from_euler(0, 0, 2 * kPi * uniform01(rng));
    box_construction_phase_ = uniform(rng, 0, 2 * kPi);
    box_constants_drawn_ = true;
  }
  const AgentTraits& traits = agent_.traits();
  const btVector3 room_point = uniform_room_point(rng, half_width);
  const btVector3 agent(room_point.x(), room_point.y(), traits.initial_position.z());
  btVector3 goal = uniform_room_point(rng, half_width);
  for (long attempt = 0; planar_distance(goal, agent) < spacing; ++attempt) {
    if (attempt >= kMaxPlacementAttempts) {
      throw std::runtime_error("Reach: no goal position reach_spacing=" + std::to_string(spacing) +
                               " m from the agent after " + std::to_string(kMaxPlacementAttempts) +
                               " draws");
    }
    goal = uniform_room_point(rng, half_width);
  }
  // Heading towards the goal plus U(−π, π): effectively uniform (docs/environments.md#reach).
  const double yaw = std::atan2(goal.y() - agent.y(), goal.x() - agent.x()) + traits.initial_yaw +
                     uniform(rng, -kPi, kPi);
  const int box_count = box_ ? 1 : 0;
  // The fork samples the obstacles before it moves agent and goal: their
  // clearances hold from the stale positions, not from this spawn and goal.
  const bool stale = description_.obstacle_clearance_from == "stale";
  const std::vector<btVector3> obstacles =
      sample_obstacle_positions(rng, box_count + description_.zones, stale ? stale_agent_ : agent,
                                stale ? stale_goal_ : goal, spacing, spacing, half_width);

  layout.agent_position = to_vec3(agent);
  layout.agent_orientation = to_quat(quaternion_from_euler(0, 0, yaw));
  const bool barrier = description_.zone_layout == "barrier";
  if (barrier) {
    // The fork samples as above (using the random numbers), then overwrites
    // the spawn and every zone with its fixed map.
    layout.agent_position = {kBarrierSpawn[0], kBarrierSpawn[1], traits.initial_position.z()};
  }
  // The fork draws the goal as above, for the clearances, and then replaces it
  // by the next corner.
  if (description_.goal_scheme == "corners") goal = next_corner();
  layout.goal = to_vec3(goal);
  layout.box.reset();
  if (box_) {
    BoxPlacement box;
    box.position = to_vec3(obstacles[0]);
    // Restoring the first reset's snapshot brings back the spawn yaw (docs/environments.md#reset).
    box.orientation = to_quat(box_spawn_orientation_);
    // docs/environments.md#moving-box: a fresh phase each episode (held), or φ drawn once.
    box.phase = box_clock_ == BoxClock::kEpisodePhase ? uniform(rng, 0, 2 * kPi)
                                                      : box_construction_phase_;
    layout.box = box;
  }
  layout.zones.clear();
  for (size_t i = static_cast<size_t>(box_count); i < obstacles.size(); ++i) {
    const size_t zone = i - static_cast<size_t>(box_count);
    layout.zones.push_back(barrier ? Vec3{kBarrierZones[zone][0], kBarrierZones[zone][1], 0}
                                   : to_vec3(obstacles[i]));
  }
  layout.d_prev = planar_distance(goal, to_bt(layout.agent_position));
}

void ReachTask::place(const Layout& layout, double clock_seconds) {
  if (box_) {
    require_unused_fields(layout, "Reach", {"goal", "box", "zones", "d_prev"});
    if (!layout.box) throw std::invalid_argument("Reach layout: 'box' is required");
  } else {
    require_unused_fields(layout, "Reach without a Box", {"goal", "zones", "d_prev"});
  }
  if (!layout.goal) throw std::invalid_argument("Reach layout: 'goal' is required");
  require_count("Reach", "zones", layout.zones.size(), static_cast<size_t>(zones_.count()));
  const btVector3 agent = to_bt(layout.agent_position);
  agent_.set_base_pose(agent, to_bt(layout.agent_orientation));
  goal_ = to_bt(*layout.goal);
  zone_placement_.clear();
  for (const Vec3& v : layout.zones) zone_placement_.push_back(to_bt(v));
  zones_.place(zone_placement_);
  if (box_) {
    box_->place(to_bt(layout.box->position), to_bt(layout.box->orientation), layout.box->phase,
                clock_seconds);
  }
  // d_prev is stored before the reset's engine step (golden README).
  d_prev_ = layout.d_prev.value_or(planar_distance(goal_, agent));

  // What the fork's next reset finds when it samples the obstacles: it first
  // restores the snapshot of its first reset (that reset's spawn and goal);
  // then the Ball's own reset moves the Ball back to its stored initial
  // position, which every Reach reset overwrites with the new spawn.
  if (!placed_once_ || description_.agent == "Ball") stale_agent_ = agent;
  if (!placed_once_) stale_goal_ = goal_;
  placed_once_ = true;
}

void ReachTask::respawn_goal(Rng& rng) {
  if (description_.goal_scheme == "corners") {
    goal_ = next_corner();
    return;
  }
  const btVector3 agent = agent_.position();
  const double clearance = description_.goal_respawn_clearance;
  for (long attempt = 0;; ++attempt) {
    if (attempt >= kMaxPlacementAttempts) {
      throw std::runtime_error("Reach: no free goal position goal_respawn_clearance=" +
                               std::to_string(clearance) + " m from agent, Box and zones after " +
                               std::to_string(kMaxPlacementAttempts) + " draws");
    }
    const btVector3 goal = uniform_room_point(rng, description_.placement_half_width);
    const MovingBox* box = hazard_box();
    bool clear = planar_distance(goal, agent) > clearance &&
                 (box == nullptr || planar_distance(goal, box->position()) > clearance);
    for (const btVector3& zone : hazard_zones().positions()) {
      clear = clear && planar_distance(goal, zone) > clearance;
    }
    if (clear) {
      goal_ = goal;
      return;
    }
  }
}

TaskOutcome ReachTask::evaluate(Rng& rng) {
  const btVector3 p = agent_.position();
  TaskOutcome outcome;
  const double d = planar_distance(goal_, p);
  outcome.reward = description_.reach_reward_scale * (d_prev_ - d) + 0.01 * agent_.specific_reward();
  d_prev_ = d;

  const MovingBox* box = hazard_box();
  const int box_contact =
      box != nullptr && world_.contact_points(box->collider(), agent_.colliders()) > 0 ? 1 : 0;
  const int collisions = box_contact + hazard_zones().collisions(p, agent_.traits().collision_radius);
  const double out_of_range = p.z() > description_.max_altitude ? 1.0 : 0.0;
  terms_[0].value = collisions;
  terms_[1].value = collisions;
  terms_[2].value = out_of_range;
  outcome.cost = std::min(1.0, (description_.count_collisions ? collisions : 0) +
                                   (description_.count_out_of_range ? out_of_range : 0.0));

  // Goal reached (docs/environments.md#one-step, item 9): bonus, new goal, the episode goes on.
  if (d < description_.goal_radius && agent_.linear_velocity().length() < description_.goal_max_speed) {
    outcome.reward += description_.goal_bonus;
    respawn_goal(rng);
    d_prev_ = planar_distance(goal_, p);
  }
  return outcome;
}

void ReachTask::write_observation(std::span<double> out) const {
  const auto rays = static_cast<size_t>(lidar_rays());
  const auto bins = static_cast<size_t>(sensor_bins());
  const btVector3 p = agent_.position();
  if (lidar_) lidar_->measure(agent_, out.first(rays));
  if (pseudo_lidar_) pseudo_lidar_->measure(p, hazard_zones().positions(), out.subspan(rays, bins));
  const double scale = 2 * world_.env_dim();
  out[rays + bins] = (goal_.x() - p.x()) / scale;
  out[rays + bins + 1] = (goal_.y() - p.y()) / scale;
}

void ReachTask::write_state(EnvState& state) const {
  state.goal = to_vec3(goal_);
  state.d_prev = d_prev_;
  if (!box_) return;
  BoxState box;
  box.position = to_vec3(box_->position());
  box.orientation = to_quat(box_->orientation());
  box.linear_velocity = to_vec3(box_->linear_velocity());
  box.angular_velocity = to_vec3(box_->angular_velocity());
  box.pivot = to_vec3(box_->pivot());
  box.clock_seconds = box_->clock_seconds();
  state.box = box;
}

void ReachTask::add_markings(std::vector<Marking>& out) const {
  out.push_back({Marking::Kind::kGoalZone, to_vec3(goal_), {}, description_.goal_radius, 0, true});
  const bool pillars = zones_.kind() == ZoneKind::kPillar;
  for (const btVector3& zone : zones_.positions()) {
    // Pillars are 2 m high (docs/environments.md#obstacles).
    out.push_back({pillars ? Marking::Kind::kPillar : Marking::Kind::kPuddle, to_vec3(zone), {},
                   zones_.radius(), pillars ? 2.0 : 0.0, true});
  }
}

}  // namespace bsg::envs
