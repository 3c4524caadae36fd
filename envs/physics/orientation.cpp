#include "envs/physics/orientation.h"

#include <cmath>

namespace bsg::envs {

btQuaternion quaternion_from_euler(double roll, double pitch, double yaw) {
  const double cr = std::cos(roll / 2), sr = std::sin(roll / 2);
  const double cp = std::cos(pitch / 2), sp = std::sin(pitch / 2);
  const double cy = std::cos(yaw / 2), sy = std::sin(yaw / 2);
  btQuaternion q(sr * cp * cy - cr * sp * sy,   // x
                 cr * sp * cy + sr * cp * sy,   // y
                 cr * cp * sy - sr * sp * cy,   // z
                 cr * cp * cy + sr * sp * sy);  // w
  return q.normalized();
}

RollPitchYaw euler_from_quaternion(const btQuaternion& q) {
  const double x = q.x(), y = q.y(), z = q.z(), w = q.w();
  const double s = -2 * (x * z - w * y);
  constexpr double kHalfPi = 1.5707963267948966;
  if (s <= -0.99999) return {0, -kHalfPi, 2 * std::atan2(x, -y)};
  if (s >= 0.99999) return {0, kHalfPi, 2 * std::atan2(-x, y)};
  return {std::atan2(2 * (y * z + w * x), w * w - x * x - y * y + z * z), std::asin(s),
          std::atan2(2 * (x * y + w * z), w * w + x * x - y * y - z * z)};
}

}  // namespace bsg::envs
