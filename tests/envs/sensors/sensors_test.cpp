// Sensor encodings (docs/environments.md#sensors) against hand-computed bearings and
// distances: the pseudo-LIDAR's bins and the LIDAR's hit fractions.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "envs/env.h"
#include "envs/sensors/pseudo_lidar_sensor.h"

namespace bsg::envs {
namespace {

TEST(PseudoLidar, ObjectDueEastLandsInTheQuarterBinWithOneMinusDistanceOverRange) {
  const PseudoLidarSensor sensor(16, 10);
  const btVector3 agent(1, -2, 0.5);
  const std::vector<btVector3> objects = {agent + btVector3(2.5, 0, -0.5)};
  std::vector<double> out(16, -1);
  sensor.measure(agent, objects, out);
  for (int b = 0; b < 16; ++b) EXPECT_EQ(out[static_cast<size_t>(b)], b == 4 ? 0.75 : 0.0) << b;
}

TEST(PseudoLidar, BinsRunClockwiseFromNorth) {
  const PseudoLidarSensor sensor(8, 5);
  const btVector3 agent(0, 0, 0);
  // Bearing β clockwise from +y; bin b covers [2πb/N, 2π(b+1)/N).
  for (int k = 0; k < 8; ++k) {
    const double bearing = 2 * std::numbers::pi * (k + 0.5) / 8;
    const btVector3 object(std::sin(bearing), std::cos(bearing), 0);
    EXPECT_EQ(sensor.bin_of(agent, object), k) << k;
  }
  // Exactly due north: the original would index bin N; it maps to bin 0.
  EXPECT_EQ(sensor.bin_of(agent, btVector3(0, 3, 0)), 0);
}

TEST(PseudoLidar, NearestObjectWinsItsBinAndFarObjectsAreIgnored) {
  const PseudoLidarSensor sensor(4, 10);
  const btVector3 agent(0, 0, 0);
  const std::vector<btVector3> objects = {{3, 3, 0}, {1, 1, 0}, {0, -10.5, 0}};
  std::vector<double> out(4, 0);
  sensor.measure(agent, objects, out);
  EXPECT_DOUBLE_EQ(out[0], 1 - std::sqrt(2.0) / 10);
  EXPECT_EQ(out[1], 0);
  EXPECT_EQ(out[2], 0);  // 10.5 m south: beyond the range
  EXPECT_EQ(out[3], 0);
}

// A wall 1 m away along ray i gives 0.8 at range 5 (docs/environments.md#sensors): the
// Ball at x = 8.9 faces the east wall's inner face at x = 9.9 with ray 6.
TEST(Lidar, WallOneMetreAwayReadsPointEight) {
  const auto env = make("SafetyBallReach-v0");
  Layout layout;
  layout.agent_position = {8.9, 0, 0.5};
  layout.goal = Vec3{-5, -5, 0};
  layout.box = BoxPlacement{{-6, 6, 0}, {0, 0, 0, 1}, 0};
  for (int i = 0; i < 8; ++i) layout.zones.push_back({-6.0 + 1.5 * i, -8, 0});
  const std::span<const double> obs = env->reset_to(layout);
  const size_t lidar = 7;  // after the Ball's 7 entries
  EXPECT_NEAR(obs[lidar + 6], 0.8, 1e-3);
  // Rays 5 and 7 (±15°) hit the same wall at 1/cos 15°.
  EXPECT_NEAR(obs[lidar + 5], 1 - 1 / std::cos(std::numbers::pi / 12) / 5, 1e-3);
  EXPECT_NEAR(obs[lidar + 7], 1 - 1 / std::cos(std::numbers::pi / 12) / 5, 1e-3);
  // Ray 0 (north): the north wall is 9.9 m away, beyond 5 m.
  EXPECT_EQ(obs[lidar + 0], 0);
  // Puddles are visual: invisible to the LIDAR even when close.
  for (size_t i = 0; i < 24; ++i) EXPECT_GE(obs[lidar + i], 0);
}

TEST(Lidar, SeesTheBoxButNotTheAgentItself) {
  const auto env = make("SafetyBallReach-v0");
  Layout layout;
  layout.agent_position = {0, 0, 0.5};
  layout.goal = Vec3{-5, -5, 0};
  // Box circle centre 3 m north; the pivot P(0) with φ = π lies 0.7 m south of
  // it, so the box is pulled towards the agent during the reset step.
  layout.box = BoxPlacement{{0, 3, 0}, {0, 0, 0, 1}, std::numbers::pi};
  for (int i = 0; i < 8; ++i) layout.zones.push_back({-6.0 + 1.5 * i, -8, 0});
  const std::span<const double> obs = env->reset_to(layout);
  const EnvState state = env->state();
  // South face of the box (half width 0.5) seen along ray 0.
  const double face_distance = state.box->position[1] - 0.5;
  EXPECT_NEAR(obs[7], 1 - face_distance / 5, 1e-2);
  // Nothing else within 5 m: the rays behind the agent read 0 (not 1, i.e. no self-hit).
  EXPECT_EQ(obs[7 + 12], 0);
}

}  // namespace
}  // namespace bsg::envs
