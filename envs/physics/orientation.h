// PyBullet's Euler-angle conventions (docs/environments.md#how-bodies-are-built), which the original
// uses for every roll/pitch/yaw it reads or sets.
#pragma once

#include <LinearMath/btQuaternion.h>
#include <LinearMath/btVector3.h>

namespace bsg::envs {

struct RollPitchYaw {
  double roll = 0;
  double pitch = 0;
  double yaw = 0;
};

// getQuaternionFromEuler: R = Rz(yaw)·Ry(pitch)·Rx(roll), normalised.
btQuaternion quaternion_from_euler(double roll, double pitch, double yaw);

// getEulerFromQuaternion, including its gimbal-lock branches (|s| ≥ 0.99999).
RollPitchYaw euler_from_quaternion(const btQuaternion& q);

}  // namespace bsg::envs
