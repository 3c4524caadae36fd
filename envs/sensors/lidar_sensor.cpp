#include "envs/sensors/lidar_sensor.h"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "envs/agents/agent.h"
#include "envs/physics/ray_fan.h"
#include "envs/physics/world.h"

namespace bsg::envs {

LidarSensor::LidarSensor(const World& world, int rays, double range_m)
    : world_(world), range_m_(range_m) {
  if (rays < 1) throw std::invalid_argument("LidarSensor: rays must be >= 1, got " +
                                            std::to_string(rays));
  if (!(range_m > 0)) throw std::invalid_argument("LidarSensor: range_m must be > 0");
  for (int i = 0; i < rays; ++i) {
    const double theta = 2 * std::numbers::pi * i / rays;  // clockwise from +y (docs/environments.md#sensors)
    directions_.emplace_back(std::sin(theta), std::cos(theta), 0);
  }
}

LidarSensor::Mount LidarSensor::mount(const Agent& agent) const {
  const AgentTraits& traits = agent.traits();
  Mount mount{agent.position(), btMatrix3x3::getIdentity(), traits.sensor_rotates};
  if (mount.rotates) {
    mount.rotation.setRotation(agent.orientation());
    mount.origin += mount.rotation * traits.sensor_offset;
  } else {
    mount.origin += traits.sensor_offset;
  }
  return mount;
}

btVector3 LidarSensor::ray_end(const Mount& mount, size_t i) const {
  return mount.origin +
         (mount.rotates ? mount.rotation * directions_[i] : directions_[i]) * range_m_;
}

void LidarSensor::measure(const Agent& agent, std::span<double> out) const {
  const Mount sensor = mount(agent);
  const RayFan colliders(world_, sensor.origin, range_m_, agent.colliders());
  for (size_t i = 0; i < directions_.size(); ++i) {
    out[i] = 1.0 - colliders.hit_fraction(ray_end(sensor, i));
  }
}

void LidarSensor::measure_reference(const Agent& agent, std::span<double> out) const {
  const Mount sensor = mount(agent);
  for (size_t i = 0; i < directions_.size(); ++i) {
    out[i] = 1.0 - world_.ray_hit_fraction(sensor.origin, ray_end(sensor, i), agent.colliders());
  }
}

}  // namespace bsg::envs
