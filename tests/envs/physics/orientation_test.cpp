// PyBullet's Euler conventions against rotation matrices built by hand.
#include <gtest/gtest.h>

#include <cmath>

#include <LinearMath/btMatrix3x3.h>

#include "envs/physics/orientation.h"

namespace bsg::envs {
namespace {

btMatrix3x3 rotation_x(double a) { return {1, 0, 0, 0, std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a)}; }
btMatrix3x3 rotation_y(double a) { return {std::cos(a), 0, std::sin(a), 0, 1, 0, -std::sin(a), 0, std::cos(a)}; }
btMatrix3x3 rotation_z(double a) { return {std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a), 0, 0, 0, 1}; }

TEST(Orientation, QuaternionFromEulerIsRzRyRx) {
  const double roll = 0.3, pitch = -0.7, yaw = 2.1;
  const btMatrix3x3 expected = rotation_z(yaw) * rotation_y(pitch) * rotation_x(roll);
  const btMatrix3x3 actual(quaternion_from_euler(roll, pitch, yaw));
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(actual[r][c], expected[r][c], 1e-14) << r << "," << c;
  }
}

TEST(Orientation, EulerRoundTripAwayFromGimbalLock) {
  const RollPitchYaw angles = euler_from_quaternion(quaternion_from_euler(-1.2, 0.4, -2.9));
  EXPECT_NEAR(angles.roll, -1.2, 1e-12);
  EXPECT_NEAR(angles.pitch, 0.4, 1e-12);
  EXPECT_NEAR(angles.yaw, -2.9, 1e-12);
}

TEST(Orientation, PureYawQuaternionHasHalfAngleZ) {
  const btQuaternion q = quaternion_from_euler(0, 0, M_PI);
  EXPECT_NEAR(q.z(), 1.0, 1e-15);
  EXPECT_NEAR(q.w(), 0.0, 1e-15);
}

TEST(Orientation, GimbalLockBranchReportsZeroRoll) {
  const RollPitchYaw angles = euler_from_quaternion(quaternion_from_euler(0, M_PI / 2, 0.5));
  EXPECT_DOUBLE_EQ(angles.roll, 0.0);
  EXPECT_NEAR(angles.pitch, M_PI / 2, 1e-12);
}

}  // namespace
}  // namespace bsg::envs
