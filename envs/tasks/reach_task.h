// Reach (docs/environments.md#reach, `ReachGoalTask`): reach a goal zone in the SmallRoom
// while avoiding 8 puddles (pillars for the Drone) and a moving Box, sensed
// through a 24-ray LIDAR and a 24-bin pseudo-LIDAR. A reached goal pays +5 and
// respawns; the episode goes on.
//
// Parameters (docs/environments.md#reach, #moving-box; EnvDescription keys in brackets):
//   goal radius           1.3 m (goal_radius); bonus +5 (goal_bonus); respawn
//                         clearance > 1.5 m (goal_respawn_clearance)
//   goal scheme           random in the room (goal_scheme random), or the fork's
//                         two corners (−6, 6), (6, 6) in turn (corners)
//   placement clearances  2.5 m (reach_spacing: agent–goal, agent–obstacle,
//                         obstacle–obstacle/goal) in [−7, 7]² (placement_half_width)
//                         measured from this episode's spawn and drawn goal, or
//                         (obstacle_clearance_from stale, the fork) from where agent
//                         and goal stood before the reset moved them
//   obstacles             the Box (box; pivot circle box_circle_radius 0.7 m) and
//                         8 zones (zones, zone_type, zone_radius)
//   reward                1·(d_prev − d) (reach_reward_scale) + 0.01·s_agent
//   sensors               LIDAR 24 rays, 5 m (lidar_rays, lidar_range; 0 rays: none);
//                         pseudo-LIDAR 24 bins, 5 m over the zones (reach_sensor_bins,
//                         reach_sensor_range; 0 bins: none)
//   task observation      (goal − agent)_xy / (2·env_dim)
//   out of range          agent z > 2 (max_altitude; cost_out_of_range)
//   Box clock             EnvOptions::box_clock (phase per episode, or simulated time)
//   physics               1 sub-step of 1/60 s
//   shared hazards        MultiGoal (docs/multi_agent.md#several-robots-on-reach): a task
//                         built with `hazards` has no zones or Box of its own; it
//                         senses, costs and respawns its goal against those of `hazards`
#pragma once

#include <array>
#include <optional>

#include "envs/description/env_description.h"
#include "envs/sensors/lidar_sensor.h"
#include "envs/tasks/moving_box.h"
#include "envs/sensors/pseudo_lidar_sensor.h"
#include "envs/tasks/task.h"
#include "envs/tasks/zone_obstacles.h"

namespace bsg::envs {

class ReachTask final : public Task {
 public:
  // `hazards`: the task whose zones and Box this one shares (then `description`
  // must have zones 0 and no Box); nullptr: its own, as in the single-agent env.
  ReachTask(World& world, Agent& agent, const EnvDescription& description, BoxClock box_clock,
            const ReachTask* hazards = nullptr);

  int observation_dim() const override { return lidar_rays() + sensor_bins() + 2; }
  std::span<const CostTerm> cost_terms() const override { return terms_; }
  void sample_layout(Rng& rng, Layout& layout) override;
  void place(const Layout& layout, double clock_seconds) override;
  void before_physics(double clock_seconds) override {
    if (box_) box_->move(clock_seconds);
  }
  TaskOutcome evaluate(Rng& rng) override;
  void write_observation(std::span<double> out) const override;
  void write_state(EnvState& state) const override;

  void add_markings(std::vector<Marking>& out) const override;

 private:
  // Draws a goal > 1.5 m from the agent and from every obstacle (docs/environments.md#reach),
  // or takes the next corner (goal_scheme corners).
  void respawn_goal(Rng& rng);
  // The fork's update_goal: (6, 6) if the flag is set, else (−6, 6); then the
  // flag flips. The flag is never reset, not even between episodes.
  btVector3 next_corner();
  const ZoneObstacles& hazard_zones() const { return hazards_ ? hazards_->zones_ : zones_; }
  const MovingBox* hazard_box() const {
    const std::optional<MovingBox>& box = hazards_ ? hazards_->box_ : box_;
    return box ? &*box : nullptr;
  }
  int lidar_rays() const { return lidar_ ? lidar_->rays() : 0; }
  int sensor_bins() const { return pseudo_lidar_ ? pseudo_lidar_->bins() : 0; }

  World& world_;
  Agent& agent_;
  const EnvDescription description_;
  BoxClock box_clock_;
  std::optional<LidarSensor> lidar_;
  std::optional<PseudoLidarSensor> pseudo_lidar_;
  std::optional<MovingBox> box_;
  ZoneObstacles zones_;
  const ReachTask* hazards_ = nullptr;  // shares its zones and Box (MultiGoal)
  std::vector<btVector3> zone_placement_;  // reused by place()
  btVector3 goal_{0, 0, 0};
  double d_prev_ = 0;
  bool corner_flag_ = false;
  // obstacle_clearance_from stale: the agent's and the goal's positions when
  // the fork's reset samples the obstacles (docs/environments.md#the-fork-variant).
  btVector3 stale_agent_{0, 0, 0};
  btVector3 stale_goal_{0, 0, 0};
  bool placed_once_ = false;
  // Drawn once, at the first sampled reset: the Box's spawn yaw (the original
  // draws it at construction) and, with the simulated clock, its phase φ.
  bool box_constants_drawn_ = false;
  btQuaternion box_spawn_orientation_ = btQuaternion::getIdentity();
  double box_construction_phase_ = 0;
  std::array<CostTerm, 3> terms_{CostTerm{"number_collisions", 0}, CostTerm{"cost_collisions", 0},
                                 CostTerm{"cost_out_of_range", 0}};
};

}  // namespace bsg::envs
