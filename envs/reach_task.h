// Reach (docs/environments.md#reach, `ReachGoalTask`): reach a goal zone in the SmallRoom
// while avoiding 8 puddles (pillars for the Drone) and a moving Box, sensed
// through a 24-ray LIDAR and a 24-bin pseudo-LIDAR. A reached goal pays +5 and
// respawns; the episode goes on.
//
// Parameters (docs/environments.md#reach, #moving-box):
//   goal radius           1.3 m; bonus +5; respawn clearance > 1.5 m
//   placement clearances  2.5 m (agent–goal, agent–obstacle, obstacle–obstacle/goal)
//   reward                (d_prev − d) + 0.01·s_agent
//   sensors               LIDAR 24 rays, 5 m; pseudo-LIDAR 24 bins, 5 m (zones)
//   task observation      (goal − agent)_xy / (2·env_dim)
//   out of range          agent z > 2 (cost_out_of_range)
//   Box clock             EnvOptions::box_clock (phase per episode, or simulated time)
//   physics               1 sub-step of 1/60 s
#pragma once

#include <array>

#include "lidar_sensor.h"
#include "moving_box.h"
#include "pseudo_lidar_sensor.h"
#include "task.h"
#include "zone_obstacles.h"

namespace bsg::envs {

class ReachTask final : public Task {
 public:
  static constexpr int kZones = 8;
  static constexpr double kGoalRadius = 1.3;
  static constexpr double kGoalBonus = 5.0;
  static constexpr double kRespawnClearance = 1.5;
  static constexpr double kPlacementClearance = 2.5;
  static constexpr double kMaxGoalSpeed = 5.0;  // 3-d speed, practically always met (docs/environments.md#kept-quirks, item 13)
  static constexpr double kMaxAltitude = 2.0;

  ReachTask(World& world, Agent& agent, ZoneKind zones, BoxClock box_clock);

  int observation_dim() const override { return lidar_.rays() + pseudo_lidar_.bins() + 2; }
  std::span<const CostTerm> cost_terms() const override { return terms_; }
  void sample_layout(Rng& rng, Layout& layout) override;
  void place(const Layout& layout, double clock_seconds) override;
  void before_physics(double clock_seconds) override { box_.move(clock_seconds); }
  TaskOutcome evaluate(Rng& rng) override;
  void write_observation(std::span<double> out) const override;
  void write_state(EnvState& state) const override;

  void add_markings(std::vector<Marking>& out) const override;

 private:
  // Draws a goal > 1.5 m from the agent and from every obstacle (docs/environments.md#reach).
  void respawn_goal(Rng& rng);

  World& world_;
  Agent& agent_;
  BoxClock box_clock_;
  LidarSensor lidar_;
  PseudoLidarSensor pseudo_lidar_;
  MovingBox box_;
  ZoneObstacles zones_;
  btVector3 goal_{0, 0, 0};
  double d_prev_ = 0;
  // Drawn once, at the first sampled reset: the Box's spawn yaw (the original
  // draws it at construction) and, with the simulated clock, its phase φ.
  bool box_constants_drawn_ = false;
  btQuaternion box_spawn_orientation_ = btQuaternion::getIdentity();
  double box_construction_phase_ = 0;
  std::array<CostTerm, 3> terms_{CostTerm{"number_collisions", 0}, CostTerm{"cost_collisions", 0},
                                 CostTerm{"cost_out_of_range", 0}};
};

// Puddles for the Ball, Car and Ant; pillars for the Drone (docs/environments.md#the-sixteen-environments).
TaskBlueprint reach_task(ZoneKind zones);

}  // namespace bsg::envs
