#include "lidar_sensor.h"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include <LinearMath/btMatrix3x3.h>

#include "agent.h"
#include "world.h"

namespace bsg::envs {

LidarSensor::LidarSensor(const World& world, int rays, double range_m)
    : world_(world), range_m_(range_m) {
  if (rays < 1) throw std::invalid_argument("LidarSensor: rays must be >= 1, got " +
                                            std::to_string(rays));
  if (!(range_m > 0)) throw std::invalid_argument("LidarSensor: range_m must be > 0");
  for (int i = 0; i < rays; ++i) {
    const double theta = 2 * std::numbers::pi * i / rays;  // clockwise from +y (spec §6)
    directions_.emplace_back(std::sin(theta), std::cos(theta), 0);
  }
}

void LidarSensor::measure(const Agent& agent, std::span<double> out) const {
  const AgentTraits& traits = agent.traits();
  btVector3 start = agent.position();
  btMatrix3x3 rotation = btMatrix3x3::getIdentity();
  if (traits.sensor_rotates) {
    rotation.setRotation(agent.orientation());
    start += rotation * traits.sensor_offset;
  } else {
    start += traits.sensor_offset;
  }
  for (size_t i = 0; i < directions_.size(); ++i) {
    const btVector3 end = start + (traits.sensor_rotates ? rotation * directions_[i]
                                                         : directions_[i]) * range_m_;
    out[i] = 1.0 - world_.ray_hit_fraction(start, end, agent.colliders());
  }
}

}  // namespace bsg::envs
