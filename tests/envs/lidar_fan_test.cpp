// The LIDAR's shared-candidate ray casts (RayFan, LidarSensor::measure) return
// what one Bullet rayTest per ray returns (World::ray_hit_fraction,
// LidarSensor::measure_reference), bit for bit, over many random poses in every
// Reach world: upright and tilted sensors, next to the Box, the walls and the
// corners, and at ground level, so that the rays hit the Box, the walls and the ground.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <numbers>
#include <string>
#include <vector>

#include <BulletCollision/CollisionDispatch/btCollisionWorld.h>
#include <BulletCollision/NarrowPhaseCollision/btRaycastCallback.h>
#include <BulletDynamics/Featherstone/btMultiBodyDynamicsWorld.h>

#include "common/random.h"
#include "envs/agent.h"
#include "envs/assembled_env.h"
#include "envs/env.h"
#include "envs/lidar_sensor.h"
#include "envs/ray_fan.h"
#include "envs/world.h"

namespace bsg::envs {
namespace {

bool same_bits(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

// Which collider the generic ray test finds closest, to show the rays cover
// every kind of collider (the fraction alone does not say).
class ClosestObject : public btCollisionWorld::ClosestRayResultCallback {
 public:
  ClosestObject(const btVector3& from, const btVector3& to,
                std::span<const btCollisionObject* const> ignore)
      : ClosestRayResultCallback(from, to), ignore_(ignore) {
    m_flags |= btTriangleRaycastCallback::kF_UseGjkConvexCastRaytest;
    m_collisionFilterGroup = kAllGroups;
    m_collisionFilterMask = kAllGroups;
  }
  bool needsCollision(btBroadphaseProxy* proxy) const override {
    const auto* object = static_cast<const btCollisionObject*>(proxy->m_clientObject);
    for (const btCollisionObject* own : ignore_) {
      if (own == object) return false;
    }
    return ClosestRayResultCallback::needsCollision(proxy);
  }

 private:
  std::span<const btCollisionObject* const> ignore_;
};

btQuaternion random_orientation(Rng& rng) {
  // Uniform on the sphere of unit quaternions (Shoemake).
  const double u1 = uniform01(rng), u2 = uniform(rng, 0, 2 * std::numbers::pi),
               u3 = uniform(rng, 0, 2 * std::numbers::pi);
  return {std::sqrt(1 - u1) * std::sin(u2), std::sqrt(1 - u1) * std::cos(u2),
          std::sqrt(u1) * std::sin(u3), std::sqrt(u1) * std::cos(u3)};
}

struct HitCounts {
  long rays = 0, ground = 0, walls = 0, box = 0, mismatches = 0;
};

class LidarFanInReach : public testing::TestWithParam<std::string> {};

TEST_P(LidarFanInReach, MatchesOneRayTestPerRayBitForBitOverRandomPoses) {
  const auto env = make(GetParam());
  auto& assembled = static_cast<AssembledEnv&>(*env);
  World& world = assembled.world();
  Agent& agent = assembled.agent();
  const LidarSensor lidar(world, 24, 5);
  const bool tilts = agent.traits().sensor_rotates;
  Rng rng(7);
  std::vector<double> action(static_cast<size_t>(env->spec().action_dim));
  std::array<double, 24> fast{};
  std::array<double, 24> reference{};
  HitCounts counts;

  for (int episode = 0; episode < 20; ++episode) {
    env->reset(static_cast<std::uint64_t>(episode));
    // A few steps so that the Box is anywhere between its random spawn yaw
    // and yaw 0, and its broadphase box has been updated by the engine.
    const int steps = 1 + 3 * episode;
    for (int s = 0; s < steps; ++s) {
      for (double& a : action) a = uniform(rng, -1, 1);
      env->step(action);
    }
    const btCollisionObject* box = nullptr;
    const btCollisionObjectArray& objects = world.dynamics().getCollisionObjectArray();
    for (int i = 0; i < objects.size(); ++i) {
      const btCollisionObject* object = objects[i];
      const auto own = agent.colliders();
      if (!object->isStaticObject() && std::find(own.begin(), own.end(), object) == own.end()) {
        box = object;
      }
    }
    ASSERT_NE(box, nullptr);
    const btVector3 box_centre = box->getWorldTransform().getOrigin();

    for (int pose = 0; pose < 250; ++pose) {
      btVector3 com;
      const int kind = pose % 4;
      if (kind == 0) {  // around the Box, within a few metres
        const double angle = uniform(rng, 0, 2 * std::numbers::pi);
        const double distance = uniform(rng, 0.4, 4);
        com = box_centre + btVector3(distance * std::sin(angle), distance * std::cos(angle),
                                     uniform(rng, 0.05, 2.0));
      } else if (kind == 1) {  // near the walls and corners
        com = btVector3(uniform(rng, 5, 9.85) * (uniform01(rng) < 0.5 ? -1 : 1),
                        uniform(rng, 5, 9.85) * (uniform01(rng) < 0.5 ? -1 : 1),
                        uniform(rng, 0.05, 2.5));
      } else if (kind == 2) {  // anywhere, including above the walls
        com = btVector3(uniform(rng, -9.8, 9.8), uniform(rng, -9.8, 9.8), uniform(rng, 0.05, 3));
      } else {  // at ground level: rays start on, just above or just below it
        com = btVector3(uniform(rng, -9.8, 9.8), uniform(rng, -9.8, 9.8),
                        uniform(rng, -0.01, 0.01));
      }
      const btQuaternion orientation =
          tilts && pose % 3 != 0
              ? random_orientation(rng)
              : btQuaternion(btVector3(0, 0, 1), uniform(rng, 0, 2 * std::numbers::pi));
      agent.set_base_pose(com, orientation);

      lidar.measure(agent, fast);
      lidar.measure_reference(agent, reference);
      for (size_t i = 0; i < fast.size(); ++i) {
        if (!same_bits(fast[i], reference[i])) ++counts.mismatches;
      }

      // Classify the closest hits along the same rays.
      btMatrix3x3 rotation = btMatrix3x3::getIdentity();
      btVector3 origin = agent.position();
      if (tilts) {
        rotation.setRotation(agent.orientation());
        origin += rotation * agent.traits().sensor_offset;
      } else {
        origin += agent.traits().sensor_offset;
      }
      for (int i = 0; i < 24; ++i) {
        const double theta = 2 * std::numbers::pi * i / 24;
        const btVector3 to =
            origin + rotation * btVector3(std::sin(theta), std::cos(theta), 0) * 5.0;
        ClosestObject closest(origin, to, agent.colliders());
        world.dynamics().rayTest(origin, to, closest);
        ++counts.rays;
        if (!closest.hasHit()) continue;
        if (closest.m_collisionObject == box) {
          ++counts.box;
        } else if (closest.m_collisionObject == world.ground()) {
          ++counts.ground;
        } else {
          ++counts.walls;
        }
      }
    }
  }
  EXPECT_EQ(counts.mismatches, 0) << "of " << counts.rays << " rays";
  EXPECT_GT(counts.box, 1000);
  EXPECT_GT(counts.walls, 1000);
  // Horizontal rays of an upright sensor reach the ground only when they
  // start at its surface; a tilted one sees it often.
  EXPECT_GT(counts.ground, tilts ? 10000 : 100);
  std::cout << "[lidar fan] " << GetParam() << ": " << counts.rays << " rays, closest hits: box "
            << counts.box << ", walls " << counts.walls << ", ground " << counts.ground << "\n";
}

INSTANTIATE_TEST_SUITE_P(EveryReachWorld, LidarFanInReach,
                         testing::Values("SafetyBallReach-v0", "SafetyCarReach-v0",
                                         "SafetyDroneReach-v0", "SafetyAntReach-v0"),
                         [](const testing::TestParamInfo<std::string>& info) {
                           std::string name = info.param;
                           for (char& c : name) {
                             if (c == '-') c = '_';
                           }
                           return name;
                         });

TEST(RayFan, KeepsOnlyTheCollidersWhoseBoxesLieWithinReach) {
  const World world(WorldLayout::kSmallRoom, 1);
  // Room centre: the walls (inner faces at ±9.9) are beyond 5 m; only the ground is near.
  EXPECT_EQ(RayFan(world, {0, 0, 0.5}, 5, {}).candidate_count(), 1);
  // Near the east wall: ground and that wall.
  EXPECT_EQ(RayFan(world, {7, 0, 0.5}, 5, {}).candidate_count(), 2);
  // Near the north-east corner: ground and two walls.
  EXPECT_EQ(RayFan(world, {7, 7, 0.5}, 5, {}).candidate_count(), 3);
  // Ignored colliders are never candidates.
  const std::array<const btCollisionObject*, 1> ground{world.ground()};
  EXPECT_EQ(RayFan(world, {0, 0, 0.5}, 5, ground).candidate_count(), 0);
}

TEST(RayFan, RaysLongerThanItsReachTakeTheGenericPathAndStillMatch) {
  const World world(WorldLayout::kSmallRoom, 1);
  const btVector3 origin(0, 0, 0.5);
  const RayFan fan(world, origin, 5, {});
  ASSERT_EQ(fan.candidate_count(), 1);  // the ground only: the walls are 9.9 m away
  // 12 m east: reaches the east wall, which is not a candidate.
  const btVector3 to(12, 0, 0.5);
  const double expected = world.ray_hit_fraction(origin, to, {});
  EXPECT_LT(expected, 1);
  EXPECT_TRUE(same_bits(fan.hit_fraction(to), expected));
}

TEST(RayFan, FallsBackToOneRayTestPerRayWhenManyCollidersAreNear) {
  World world(WorldLayout::kSmallRoom, 1);
  // A ring of 20 pillars around the origin: more than kMaxCandidates.
  for (int k = 0; k < 20; ++k) {
    const double angle = 2 * std::numbers::pi * k / 20;
    world.add_static_box({0.2, 0.2, 1}, {3 * std::cos(angle), 3 * std::sin(angle), 1}, angle, 0.5,
                         0);
  }
  const btVector3 origin(0.3, -0.2, 0.6);
  const RayFan fan(world, origin, 5, {});
  EXPECT_EQ(fan.candidate_count(), -1);
  Rng rng(3);
  int hits = 0;
  for (int i = 0; i < 2000; ++i) {
    btVector3 direction(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -0.5, 0.5));
    direction.normalize();
    const btVector3 to = origin + direction * 5.0;
    const double expected = world.ray_hit_fraction(origin, to, {});
    EXPECT_TRUE(same_bits(fan.hit_fraction(to), expected)) << "ray " << i;
    hits += expected < 1 ? 1 : 0;
  }
  EXPECT_GT(hits, 500);
}

TEST(RayFan, MatchesOneRayTestPerRayAmongAFewRotatedBoxes) {
  World world(WorldLayout::kSmallRoom, 1);
  Rng rng(11);
  for (int k = 0; k < 6; ++k) {
    world.add_static_box({uniform(rng, 0.1, 0.8), uniform(rng, 0.1, 0.8), uniform(rng, 0.2, 1)},
                         {uniform(rng, -4, 4), uniform(rng, -4, 4), uniform(rng, 0.2, 1)},
                         uniform(rng, 0, 2 * std::numbers::pi), 0.5, 0);
  }
  int hits = 0;
  for (int i = 0; i < 5000; ++i) {
    const btVector3 origin(uniform(rng, -6, 6), uniform(rng, -6, 6), uniform(rng, 0, 2));
    const RayFan fan(world, origin, 5, {});
    ASSERT_GE(fan.candidate_count(), 0);
    btVector3 direction(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1));
    direction.normalize();
    const btVector3 to = origin + direction * uniform(rng, 0.5, 5);
    const double expected = world.ray_hit_fraction(origin, to, {});
    EXPECT_TRUE(same_bits(fan.hit_fraction(to), expected)) << "ray " << i;
    hits += expected < 1 ? 1 : 0;
  }
  EXPECT_GT(hits, 1500);
}

}  // namespace
}  // namespace bsg::envs
