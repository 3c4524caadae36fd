#include "envs/sensors/pseudo_lidar_sensor.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "envs/physics/planar_geometry.h"

namespace bsg::envs {

PseudoLidarSensor::PseudoLidarSensor(int bins, double range_m) : bins_(bins), range_m_(range_m) {
  if (bins < 1) throw std::invalid_argument("PseudoLidarSensor: bins must be >= 1, got " +
                                            std::to_string(bins));
  if (!(range_m > 0)) throw std::invalid_argument("PseudoLidarSensor: range_m must be > 0");
}

int PseudoLidarSensor::bin_of(const btVector3& agent, const btVector3& object) const {
  // The original's form: β = atan2(x_a − x_o, y_a − y_o) + π, the bearing of
  // object − agent clockwise from +y, in (0, 2π].
  const double bearing =
      std::atan2(agent.x() - object.x(), agent.y() - object.y()) + std::numbers::pi;
  const int bin = static_cast<int>(std::floor(bearing / (2 * std::numbers::pi / bins_)));
  return bin >= bins_ ? 0 : bin;
}

void PseudoLidarSensor::measure(const btVector3& agent, std::span<const btVector3> objects,
                                std::span<double> out) const {
  std::fill(out.begin(), out.end(), 0.0);
  for (const btVector3& object : objects) {
    const double distance = planar_distance(object, agent);
    if (distance > range_m_) continue;
    double& value = out[static_cast<size_t>(bin_of(agent, object))];
    value = std::max(value, 1 - distance / range_m_);
  }
}

}  // namespace bsg::envs
