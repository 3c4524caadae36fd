// Puddles and Pillars of Reach (docs/environments.md#reach, #obstacles): visual discs or cylinders
// (no collision shape, invisible to physics and to the LIDAR) that cost when
// the agent's footprint overlaps them in the plane:
//   ‖agent − zone‖_xy − r_agent − r_zone ≤ 0  (flying over a pillar still costs).
//
// Parameters:
//   count   8
//   radius  Puddle 1.0 m, Pillar 0.45 m (Reach with the Drone), or as the
//           description's zone_radius says
#pragma once

#include <span>
#include <vector>

#include <LinearMath/btVector3.h>

namespace bsg::envs {

enum class ZoneKind { kPuddle, kPillar };

class ZoneObstacles {
 public:
  ZoneObstacles(ZoneKind kind, int count, double radius);

  ZoneKind kind() const { return kind_; }
  double radius() const { return radius_; }
  int count() const { return static_cast<int>(positions_.size()); }
  std::span<const btVector3> positions() const { return positions_; }

  void place(std::span<const btVector3> positions);
  // Number of zones the agent's disc of `agent_radius` overlaps.
  int collisions(const btVector3& agent, double agent_radius) const;

 private:
  ZoneKind kind_;
  double radius_;
  std::vector<btVector3> positions_;
};

}  // namespace bsg::envs
