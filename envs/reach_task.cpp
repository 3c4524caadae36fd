#include "reach_task.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "layout_checks.h"
#include "orientation.h"
#include "placement_sampler.h"

namespace bsg::envs {

ReachTask::ReachTask(World& world, Agent& agent, ZoneKind zones, BoxClock box_clock)
    : world_(world),
      agent_(agent),
      box_clock_(box_clock),
      lidar_(world, 24, world.env_dim() / 2),
      pseudo_lidar_(24, world.env_dim() / 2),
      box_(world),
      zones_(zones, kZones) {}

void ReachTask::sample_layout(Rng& rng, Layout& layout) {
  constexpr double kPi = std::numbers::pi;
  if (!box_constants_drawn_) {
    box_spawn_orientation_ = quaternion_from_euler(0, 0, 2 * kPi * uniform01(rng));
    box_construction_phase_ = uniform(rng, 0, 2 * kPi);
    box_constants_drawn_ = true;
  }
  const AgentTraits& traits = agent_.traits();
  const btVector3 room_point = uniform_room_point(rng);
  const btVector3 agent(room_point.x(), room_point.y(), traits.initial_position.z());
  btVector3 goal = uniform_room_point(rng);
  while (planar_distance(goal, agent) < kPlacementClearance) goal = uniform_room_point(rng);
  // Heading towards the goal plus U(−π, π): effectively uniform (docs/environments.md#reach).
  const double yaw = std::atan2(goal.y() - agent.y(), goal.x() - agent.x()) + traits.initial_yaw +
                     uniform(rng, -kPi, kPi);
  const std::vector<btVector3> obstacles = sample_obstacle_positions(
      rng, 1 + kZones, agent, goal, kPlacementClearance, kPlacementClearance);

  layout.agent_position = to_vec3(agent);
  layout.agent_orientation = to_quat(quaternion_from_euler(0, 0, yaw));
  layout.goal = to_vec3(goal);
  BoxPlacement box;
  box.position = to_vec3(obstacles[0]);
  // Restoring the first reset's snapshot brings back the spawn yaw (docs/environments.md#reset).
  box.orientation = to_quat(box_spawn_orientation_);
  // docs/environments.md#moving-box: a fresh phase each episode (held), or φ drawn once.
  box.phase = box_clock_ == BoxClock::kEpisodePhase ? uniform(rng, 0, 2 * kPi)
                                                    : box_construction_phase_;
  layout.box = box;
  layout.zones.clear();
  for (int i = 0; i < kZones; ++i) layout.zones.push_back(to_vec3(obstacles[1 + static_cast<size_t>(i)]));
  layout.d_prev = planar_distance(goal, agent);
}

void ReachTask::place(const Layout& layout, double clock_seconds) {
  require_unused_fields(layout, "Reach", {"goal", "box", "zones", "d_prev"});
  if (!layout.goal) throw std::invalid_argument("Reach layout: 'goal' is required");
  if (!layout.box) throw std::invalid_argument("Reach layout: 'box' is required");
  require_count("Reach", "zones", layout.zones.size(), kZones);
  const btVector3 agent = to_bt(layout.agent_position);
  agent_.set_base_pose(agent, to_bt(layout.agent_orientation));
  goal_ = to_bt(*layout.goal);
  std::array<btVector3, kZones> zones;
  std::transform(layout.zones.begin(), layout.zones.end(), zones.begin(),
                 [](const Vec3& v) { return to_bt(v); });
  zones_.place(zones);
  box_.place(to_bt(layout.box->position), to_bt(layout.box->orientation), layout.box->phase,
             clock_seconds);
  // d_prev is stored before the reset's engine step (golden README).
  d_prev_ = layout.d_prev.value_or(planar_distance(goal_, agent));
}

void ReachTask::respawn_goal(Rng& rng) {
  const btVector3 agent = agent_.position();
  const btVector3 box = box_.position();
  for (long attempt = 0;; ++attempt) {
    if (attempt >= kMaxPlacementAttempts) {
      throw std::runtime_error("Reach: no free goal position after " +
                               std::to_string(kMaxPlacementAttempts) + " draws");
    }
    const btVector3 goal = uniform_room_point(rng);
    bool clear = planar_distance(goal, agent) > kRespawnClearance &&
                 planar_distance(goal, box) > kRespawnClearance;
    for (const btVector3& zone : zones_.positions()) {
      clear = clear && planar_distance(goal, zone) > kRespawnClearance;
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
  outcome.reward = (d_prev_ - d) + 0.01 * agent_.specific_reward();
  d_prev_ = d;

  const int box_contact = world_.contact_points(box_.collider(), agent_.colliders()) > 0 ? 1 : 0;
  const int collisions = box_contact + zones_.collisions(p, agent_.traits().collision_radius);
  const double out_of_range = p.z() > kMaxAltitude ? 1.0 : 0.0;
  terms_[0].value = collisions;
  terms_[1].value = collisions;
  terms_[2].value = out_of_range;
  outcome.cost = std::min(1.0, collisions + out_of_range);

  // Goal reached (docs/environments.md#one-step, item 9): bonus, new goal, the episode goes on.
  if (d < kGoalRadius && agent_.linear_velocity().length() < kMaxGoalSpeed) {
    outcome.reward += kGoalBonus;
    respawn_goal(rng);
    d_prev_ = planar_distance(goal_, p);
  }
  return outcome;
}

void ReachTask::write_observation(std::span<double> out) const {
  const auto rays = static_cast<size_t>(lidar_.rays());
  const auto bins = static_cast<size_t>(pseudo_lidar_.bins());
  const btVector3 p = agent_.position();
  lidar_.measure(agent_, out.first(rays));
  pseudo_lidar_.measure(p, zones_.positions(), out.subspan(rays, bins));
  const double scale = 2 * world_.env_dim();
  out[rays + bins] = (goal_.x() - p.x()) / scale;
  out[rays + bins + 1] = (goal_.y() - p.y()) / scale;
}

void ReachTask::write_state(EnvState& state) const {
  state.goal = to_vec3(goal_);
  state.d_prev = d_prev_;
  BoxState box;
  box.position = to_vec3(box_.position());
  box.orientation = to_quat(box_.orientation());
  box.linear_velocity = to_vec3(box_.linear_velocity());
  box.angular_velocity = to_vec3(box_.angular_velocity());
  box.pivot = to_vec3(box_.pivot());
  box.clock_seconds = box_.clock_seconds();
  state.box = box;
}

TaskBlueprint reach_task(ZoneKind zones) {
  return {"Reach", WorldLayout::kSmallRoom, 1, true,
          [zones](World& world, Agent& agent, const EnvOptions& options) {
            return std::make_unique<ReachTask>(world, agent, zones, options.box_clock);
          }};
}

void ReachTask::add_markings(std::vector<Marking>& out) const {
  out.push_back({Marking::Kind::kGoalZone, to_vec3(goal_), {}, kGoalRadius, 0, true});
  const bool pillars = zones_.kind() == ZoneKind::kPillar;
  for (const btVector3& zone : zones_.positions()) {
    // Pillars are 2 m high (docs/environments.md#obstacles).
    out.push_back({pillars ? Marking::Kind::kPillar : Marking::Kind::kPuddle, to_vec3(zone), {},
                   zones_.radius(), pillars ? 2.0 : 0.0, true});
  }
}

}  // namespace bsg::envs
