// The LIDAR's shared-candidate ray casts (RayFan, LidarSensor::measure) return
// what one Bullet rayTest per ray returns (World::ray_hit_fraction,
// LidarSensor::measure_reference) over many random poses in every Reach world:
// upright and tilted sensors, next to the Box, the walls and the corners, at
// ground level and at the height of the Box's and the walls' top edges, so that
// the rays hit (and graze) the Box, the walls and the ground. Boxes are cast in
// closed form (cast_ray_at_box), so the fractions agree to rounding, not bit
// for bit. Hit or miss agree on every ray here; only a ray within 1 mm of a
// box's surface and parallel to it could differ (tests/envs/physics/ray_box_cast_test.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include <BulletCollision/CollisionDispatch/btCollisionWorld.h>
#include <BulletCollision/CollisionShapes/btBoxShape.h>
#include <BulletCollision/CollisionShapes/btCompoundShape.h>
#include <BulletCollision/CollisionShapes/btSphereShape.h>
#include <BulletCollision/NarrowPhaseCollision/btRaycastCallback.h>
#include <BulletDynamics/Featherstone/btMultiBodyDynamicsWorld.h>

#include "common/random.h"
#include "envs/agents/agent.h"
#include "envs/assembly/assembled_env.h"
#include "envs/env.h"
#include "envs/sensors/lidar_sensor.h"
#include "envs/physics/ray_fan.h"
#include "envs/physics/world.h"

namespace bsg::envs {
namespace {

bool same_bits(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

// Largest |fast − reference| of the fractions, and rays hit by one and not the other.
struct Agreement {
  long rays = 0, hit_miss_mismatches = 0;
  double max_deviation = 0;
  void add(double fast, double reference) {
    ++rays;
    if ((fast < 1) != (reference < 1)) {
      ++hit_miss_mismatches;
    } else {
      max_deviation = std::max(max_deviation, std::fabs(fast - reference));
    }
  }
};

// The bound on |fast − reference| of a LIDAR fraction, four orders below the
// golden observation tolerance (1e-5). Measured maxima (Bullet 3.24 double):
// LidarFanInReach Ball 2.0e-13, Car 1.9e-10, Drone 1.6e-10, Ant 2.0e-13 (the
// largest where tilted sensors meet the ground at grazing incidence, where
// the fraction is most sensitive to GJK's 1e-12 stopping tolerance); rotated
// boxes 1.2e-12; compounds 1.3e-12.
constexpr double kFractionTolerance = 1e-9;

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

// Uniform in [low, high) or in (−high, −low], with even odds; the magnitude is
// drawn first (the operands of one expression are unsequenced).
double either_side(Rng& rng, double low, double high) {
  const double magnitude = uniform(rng, low, high);
  return uniform01(rng) < 0.5 ? -magnitude : magnitude;
}

// Top faces in the Reach worlds: the Box's 1.5 m above its base frame (its
// bottom face), the walls' at z = 2 (docs/environments.md#worlds).
constexpr double kBoxHeight_m = 1.5;
constexpr double kWallHeight_m = 2.0;

// Where the LIDAR's rays start for the agent's pose (LidarSensor's mount).
btVector3 sensor_origin(const Agent& agent) {
  if (!agent.traits().sensor_rotates) return agent.position() + agent.traits().sensor_offset;
  return agent.position() + btMatrix3x3(agent.orientation()) * agent.traits().sensor_offset;
}

struct HitCounts {
  long rays = 0, ground = 0, walls = 0, box = 0;
};

class LidarFanInReach : public ::testing::TestWithParam<std::string> {};

TEST_P(LidarFanInReach, MatchesOneRayTestPerRayWithinRoundingOverRandomPoses) {
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
  Agreement agreement;

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
      const int kind = pose % 5;
      if (kind == 0) {  // around the Box, within a few metres
        const double angle = uniform(rng, 0, 2 * std::numbers::pi);
        const double distance = uniform(rng, 0.4, 4);
        com = box_centre + btVector3(distance * std::sin(angle), distance * std::cos(angle),
                                     uniform(rng, 0.05, 2.0));
      } else if (kind == 1) {  // near the walls and corners
        com = btVector3{either_side(rng, 5, 9.85), either_side(rng, 5, 9.85),
                        uniform(rng, 0.05, 2.5)};
      } else if (kind == 2) {  // anywhere, including above the walls
        com = btVector3{uniform(rng, -9.8, 9.8), uniform(rng, -9.8, 9.8), uniform(rng, 0.05, 3)};
      } else if (kind == 3) {  // at ground level: rays start on, just above or just below it
        com = btVector3{uniform(rng, -9.8, 9.8), uniform(rng, -9.8, 9.8),
                        uniform(rng, -0.01, 0.01)};
      } else {  // level with the top face of the Box or of the walls, ±3 mm: grazing rays
        const double angle = uniform(rng, 0, 2 * std::numbers::pi);
        const double distance = uniform(rng, 0.6, 4.5);
        if (pose % 2 == 0) {
          com = box_centre + btVector3(distance * std::sin(angle), distance * std::cos(angle), 0);
        } else {
          com = btVector3{either_side(rng, 5.5, 9.8), uniform(rng, -9.8, 9.8), 0};
        }
        com.setZ((pose % 2 == 0 ? box_centre.z() + kBoxHeight_m : kWallHeight_m) +
                 uniform(rng, -3e-3, 3e-3));
      }
      const btQuaternion orientation =
          tilts && pose % 3 != 0 && kind != 4
              ? random_orientation(rng)
              : btQuaternion(btVector3(0, 0, 1), uniform(rng, 0, 2 * std::numbers::pi));
      agent.set_base_pose(com, orientation);
      if (kind == 4) {
        // Put the sensor itself (not the base) at that height.
        const btVector3 sensor = sensor_origin(agent);
        agent.set_base_pose(com + btVector3(0, 0, com.z() - sensor.z()), orientation);
      }

      lidar.measure(agent, fast);
      lidar.measure_reference(agent, reference);
      // LIDAR values are 1 − f: a hit is a value above 0.
      for (size_t i = 0; i < fast.size(); ++i) agreement.add(1 - fast[i], 1 - reference[i]);

      // Classify the closest hits along the same rays.
      btMatrix3x3 rotation = btMatrix3x3::getIdentity();
      if (tilts) rotation.setRotation(agent.orientation());
      const btVector3 origin = sensor_origin(agent);
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
  EXPECT_EQ(agreement.hit_miss_mismatches, 0) << "of " << agreement.rays << " rays";
  EXPECT_LE(agreement.max_deviation, kFractionTolerance);
  EXPECT_GT(counts.box, 1000);
  EXPECT_GT(counts.walls, 1000);
  // Horizontal rays of an upright sensor reach the ground only when they
  // start at its surface; a tilted one sees it often.
  EXPECT_GT(counts.ground, tilts ? 10000 : 100);
  std::cout << "[lidar fan] " << GetParam() << ": " << counts.rays << " rays, closest hits: box "
            << counts.box << ", walls " << counts.walls << ", ground " << counts.ground
            << "; max |fraction - Bullet's| " << agreement.max_deviation << "\n";
}

INSTANTIATE_TEST_SUITE_P(EveryReachWorld, LidarFanInReach,
                         ::testing::Values("SafetyBallReach-v0", "SafetyCarReach-v0",
                                         "SafetyDroneReach-v0", "SafetyAntReach-v0"),
                         [](const ::testing::TestParamInfo<std::string>& info) {
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
    btVector3 direction{uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -0.5, 0.5)};
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
  Agreement agreement;
  for (int i = 0; i < 5000; ++i) {
    const btVector3 origin{uniform(rng, -6, 6), uniform(rng, -6, 6), uniform(rng, 0, 2)};
    const RayFan fan(world, origin, 5, {});
    ASSERT_GE(fan.candidate_count(), 0);
    EXPECT_EQ(fan.closed_form_box_count(), fan.candidate_count());  // every collider is a box
    btVector3 direction{uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1)};
    direction.normalize();
    const btVector3 to = origin + direction * uniform(rng, 0.5, 5);
    const double expected = world.ray_hit_fraction(origin, to, {});
    agreement.add(fan.hit_fraction(to), expected);
    hits += expected < 1 ? 1 : 0;
  }
  EXPECT_GT(hits, 1500);
  EXPECT_EQ(agreement.hit_miss_mismatches, 0);
  EXPECT_LE(agreement.max_deviation, kFractionTolerance);
  std::cout << "[lidar fan] rotated boxes: max |fraction - Bullet's| " << agreement.max_deviation
            << "\n";
}

// Compounds as URDF links build them: several boxes with child transforms,
// and a child that is not a box (which rayTestSingle takes), with and without
// the compound's tree of child boxes.
TEST(RayFan, MatchesOneRayTestPerRayOnCompoundsOfBoxesAndOtherShapes) {
  World world(WorldLayout::kSmallRoom, 1);
  Rng rng(13);
  std::vector<std::unique_ptr<btCollisionShape>> shapes;
  std::vector<std::unique_ptr<btCollisionObject>> objects;
  for (int k = 0; k < 4; ++k) {
    auto compound = std::make_unique<btCompoundShape>(/*enableDynamicAabbTree=*/k % 2 == 0);
    for (int c = 0; c < 3; ++c) {
      btTransform child;
      child.setRotation(random_orientation(rng));
      child.setOrigin({uniform(rng, -0.6, 0.6), uniform(rng, -0.6, 0.6), uniform(rng, 0, 0.6)});
      if (c == 2 && k >= 2) {
        shapes.push_back(std::make_unique<btSphereShape>(uniform(rng, 0.1, 0.4)));
      } else {
        auto box = std::make_unique<btBoxShape>(
            btVector3{uniform(rng, 0.1, 0.5), uniform(rng, 0.1, 0.5), uniform(rng, 0.1, 0.5)});
        box->setMargin(0.001);
        shapes.push_back(std::move(box));
      }
      compound->addChildShape(child, shapes.back().get());
    }
    shapes.push_back(std::move(compound));
    auto object = std::make_unique<btCollisionObject>();
    object->setCollisionShape(shapes.back().get());
    btTransform pose;
    pose.setRotation(random_orientation(rng));
    pose.setOrigin({uniform(rng, -3, 3), uniform(rng, -3, 3), uniform(rng, 0.5, 1.5)});
    object->setWorldTransform(pose);
    world.dynamics().addCollisionObject(object.get(), kStaticGroup, kAllGroups ^ kStaticGroup);
    objects.push_back(std::move(object));
  }
  // Out of the world again before they are destroyed, whatever happens below.
  struct Removal {
    World& world;
    std::vector<std::unique_ptr<btCollisionObject>>& objects;
    ~Removal() {
      for (auto& object : objects) world.dynamics().removeCollisionObject(object.get());
    }
  } removal{world, objects};
  int hits = 0;
  Agreement agreement;
  for (int i = 0; i < 5000; ++i) {
    const btVector3 origin{uniform(rng, -5, 5), uniform(rng, -5, 5), uniform(rng, 0, 2)};
    const RayFan fan(world, origin, 5, {});
    ASSERT_GE(fan.candidate_count(), 0);
    btVector3 direction{uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -0.5, 0.5)};
    direction.normalize();
    const btVector3 to = origin + direction * uniform(rng, 0.5, 5);
    const double expected = world.ray_hit_fraction(origin, to, {});
    agreement.add(fan.hit_fraction(to), expected);
    hits += expected < 1 ? 1 : 0;
  }
  EXPECT_GT(hits, 1000);
  EXPECT_EQ(agreement.hit_miss_mismatches, 0);
  EXPECT_LE(agreement.max_deviation, kFractionTolerance);
  std::cout << "[lidar fan] compounds: max |fraction - Bullet's| " << agreement.max_deviation
            << "\n";
}

TEST(RayFan, CastsTheRoomsBoxesInClosedForm) {
  const World world(WorldLayout::kSmallRoom, 1);
  // Near the north-east corner: the ground (a compound of one box) and two walls.
  const RayFan fan(world, {7, 7, 0.5}, 5, {});
  EXPECT_EQ(fan.candidate_count(), 3);
  EXPECT_EQ(fan.closed_form_box_count(), 3);
}

}  // namespace
}  // namespace bsg::envs
