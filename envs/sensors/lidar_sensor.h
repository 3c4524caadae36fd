// LIDAR (docs/environments.md#lidar): N horizontal rays of length L cast from the agent's
// sensor mount against every collider of the world except the agent's own;
// value_i = 1 − f_i with f_i the closest-hit fraction (0 = nothing in range).
// Ray i points clockwise from world +y: (sin 2πi/N, cos 2πi/N, 0), turned by the
// base rotation for agents whose sensor rotates (Car, Drone).
//
// Parameters:
//   rays     24 (Reach)
//   range_m  env_dim/2 = 5 (Reach)
#pragma once

#include <span>
#include <vector>

#include <LinearMath/btMatrix3x3.h>
#include <LinearMath/btVector3.h>

namespace bsg::envs {

class Agent;
class World;

class LidarSensor {
 public:
  LidarSensor(const World& world, int rays, double range_m);

  int rays() const { return static_cast<int>(directions_.size()); }
  double range_m() const { return range_m_; }

  // Writes rays() values for the agent's current pose. The rays share one
  // collection of nearby colliders (RayFan) instead of one broadphase walk
  // each, and boxes are cast in closed form instead of by GJK.
  void measure(const Agent& agent, std::span<double> out) const;
  // The same values from World::ray_hit_fraction per ray (one Bullet rayTest
  // each): the straightforward path, kept as the oracle of measure() in tests.
  // measure() agrees with it to 1e-9, and on hit or miss except for a ray
  // that runs within 1 mm of a box and parallel to its surface (see RayFan).
  void measure_reference(const Agent& agent, std::span<double> out) const;

 private:
  // Where the sensor sits for the agent's pose; ray_end() gives ray i's end.
  struct Mount {
    btVector3 origin;
    btMatrix3x3 rotation;
    bool rotates;
  };
  Mount mount(const Agent& agent) const;
  btVector3 ray_end(const Mount& mount, size_t i) const;

  const World& world_;
  double range_m_;
  std::vector<btVector3> directions_;  // unit, world frame for a non-rotating mount
};

}  // namespace bsg::envs
