// LIDAR (spec §6.1): N horizontal rays of length L cast from the agent's
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

#include <LinearMath/btVector3.h>

namespace bsg::envs {

class Agent;
class World;

class LidarSensor {
 public:
  LidarSensor(const World& world, int rays, double range_m);

  int rays() const { return static_cast<int>(directions_.size()); }
  double range_m() const { return range_m_; }

  // Writes rays() values for the agent's current pose.
  void measure(const Agent& agent, std::span<double> out) const;

 private:
  const World& world_;
  double range_m_;
  std::vector<btVector3> directions_;  // unit, world frame for a non-rotating mount
};

}  // namespace bsg::envs
