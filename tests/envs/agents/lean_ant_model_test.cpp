// The Ant's lean model (env.h, PhysicsModel::kLean) against independent
// oracles: its welded base's mass properties by the parallel-axis theorem
// worked out by hand from the model's geometry (docs/environments.md#ant), the welded
// leg links against the parts they carry, and its kinematics against the
// faithful model over a horizon too short for chaos to amplify rounding.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include <BulletDynamics/Featherstone/btMultiBody.h>

#include "common/random.h"
#include "envs/agents/ant_agent.h"
#include "envs/env.h"
#include "envs/physics/world.h"
#include "../lean_model_gaps.h"

namespace bsg::envs {
namespace {

constexpr double kPi = std::numbers::pi;

std::unique_ptr<AntAgent> make_ant(World& world, PhysicsModel physics) {
  AgentOptions options;
  options.physics = physics;
  return std::make_unique<AntAgent>(world, options);
}

// Capsule of radius r and length L (the MJCF's float32 numbers) at 1000 kg/m³.
double capsule_mass(double length) {
  const double r = static_cast<float>(0.08);
  return 1000 * (4.0 / 3.0 * kPi * r * r * r + kPi * r * r * length);
}

TEST(LeanAnt, BaseWeldsTorsoAndStubsByTheParallelAxisTheorem) {
  World world(WorldLayout::kPlane200, 4);
  const auto lean = make_ant(world, PhysicsModel::kLean);
  const btMultiBody& body = lean->multibody();
  ASSERT_EQ(body.getNumLinks(), 8);  // hip+thigh and ankle+foot per leg

  // Torso: sphere r = 0.25, I = 0.4·m·r². Stub: capsule from 0 to 0.2·(±1, ±1, 0),
  // COM at 0.1·(±1, ±1, 0), own inertia (0.16394, 0.16394, 0.252698) (docs/environments.md#ant).
  const double torso_mass = 1000 * 4.0 / 3.0 * kPi * std::pow(0.25, 3);
  const double torso_inertia = 0.4 * torso_mass * 0.25 * 0.25;
  const double a = static_cast<float>(0.2);
  const double stub_mass = capsule_mass(std::sqrt(2 * a * a));
  const double d = 0.5 * a;  // COM offset along x and along y
  // Parallel axis: I_xx += m·(d_y² + d_z²), I_yy += m·(d_x² + d_z²), I_zz += m·(d_x² + d_y²);
  // the products −m·d_x·d_y cancel over the four legs (signs +, −, +, −).
  const double ixx = torso_inertia + 4 * (0.16394 + stub_mass * d * d);
  const double izz = torso_inertia + 4 * (0.252698 + stub_mass * 2 * d * d);

  EXPECT_NEAR(body.getBaseMass(), torso_mass + 4 * stub_mass, 1e-9);
  const btVector3 inertia = body.getBaseInertia();
  EXPECT_NEAR(inertia.x(), ixx, 1e-5 * ixx);
  EXPECT_NEAR(inertia.y(), ixx, 1e-5 * ixx);
  EXPECT_NEAR(inertia.z(), izz, 1e-5 * izz);
  // Magnitudes, so that a wrong formula cannot hide in the tolerance.
  EXPECT_NEAR(ixx, 1.6362 + 4 * 0.16394 + 4 * 0.0783, 2e-3);

  World faithful_world(WorldLayout::kPlane200, 4);
  const auto faithful = make_ant(faithful_world, PhysicsModel::kFaithful);
  EXPECT_NEAR(lean->total_mass_kg(), faithful->total_mass_kg(), 1e-12);
}

TEST(LeanAnt, LegLinksCarryTheThighAndFootOfTheMasslessJointLinks) {
  World world(WorldLayout::kPlane200, 4);
  const auto lean = make_ant(world, PhysicsModel::kLean);
  World faithful_world(WorldLayout::kPlane200, 4);
  const auto faithful = make_ant(faithful_world, PhysicsModel::kFaithful);
  const btMultiBody& lb = lean->multibody();
  const btMultiBody& fb = faithful->multibody();
  const double a = static_cast<float>(0.2);
  const double b = static_cast<float>(0.4);
  for (int leg = 0; leg < 4; ++leg) {
    // Faithful links 5·leg + (0 stub, 1 hip, 2 thigh, 3 ankle, 4 foot).
    EXPECT_EQ(fb.getLinkMass(5 * leg + 1), 0.0);
    EXPECT_EQ(fb.getLinkMass(5 * leg + 3), 0.0);
    EXPECT_NEAR(lb.getLinkMass(2 * leg), capsule_mass(std::sqrt(2 * a * a)), 1e-9);
    EXPECT_NEAR(lb.getLinkMass(2 * leg + 1), capsule_mass(std::sqrt(2 * b * b)), 1e-9);
    EXPECT_EQ(lb.getLinkInertia(2 * leg), fb.getLinkInertia(5 * leg + 2));
    EXPECT_EQ(lb.getLinkInertia(2 * leg + 1), fb.getLinkInertia(5 * leg + 4));
  }
}

TEST(LeanAnt, PlacesEveryLinkWhereTheFaithfulModelDoes) {
  World fw(WorldLayout::kPlane200, 4), lw(WorldLayout::kPlane200, 4);
  const auto faithful = make_ant(fw, PhysicsModel::kFaithful);
  const auto lean = make_ant(lw, PhysicsModel::kLean);
  const std::vector<double> q = {0.3, 1.2, -0.4, -0.9, 0.5, -1.4, -0.2, 0.7};
  const btQuaternion tilt(btVector3(1, 2, 3).normalized(), 0.4);
  for (AntAgent* ant : {faithful.get(), lean.get()}) {
    ant->set_base_pose(btVector3(1, -2, 0.9), tilt);
    ant->set_joint_positions(q);
  }
  for (int link = 0; link < AntAgent::kLinkCount; ++link) {
    const btTransform f = faithful->link_com_transform(link);
    const btTransform l = lean->link_com_transform(link);
    EXPECT_LT((f.getOrigin() - l.getOrigin()).length(), 1e-12) << "link " << link;
    EXPECT_LT(rotation_gap(f.getBasis(), l.getBasis()), 1e-12) << "link " << link;
  }
}

TEST(LeanAnt, FollowsTheFaithfulTrajectoryThroughTheLanding) {
  // Without actions no joint limit is reached. The first 7 steps are free fall
  // (the feet touch down in step 8), where the models agree to rounding; then
  // the landing's contact forces turn every body, so the welded masses and
  // inertias (and the thigh and foot links) are what is checked. Contacts are
  // solved in another row order (one base collider instead of five), which
  // leaves rounding-level differences that mostly grow slowly (seed 3 after
  // 40 steps: 1.6e-8 m and 3.6e-7 rad). Some landings amplify them more (seed
  // 4, no joint limit reached: 8e-4 rad), as the random-torque case below.
  EXPECT_LT(largest_lean_gap("SafetyAntRun-v0", 7, 3, /*random_actions=*/false).joints, 1e-12);
  for (std::uint64_t seed : {3u, 5u, 6u, 7u}) {
    const TrajectoryGap gap = largest_lean_gap("SafetyAntRun-v0", 40, seed, /*random_actions=*/false);
    EXPECT_LT(gap.position, 1e-6) << "seed " << seed;
    EXPECT_LT(gap.joints, 1e-5) << "seed " << seed;
    EXPECT_LT(gap.velocity, 1e-5) << "seed " << seed;
  }
}

TEST(LeanAnt, FollowsTheFaithfulTrajectoryWithRandomTorques) {
  // 250 N·m on light legs drive joints into their limits within the first
  // step; the projected Gauss-Seidel solver's 5 iterations do not converge,
  // so the order of its rows (which differs) shows at 1e-7 rad at once and
  // chaos amplifies it ~10x per 10 steps. Over 12 steps (0.2 s; the joints
  // move by about 1 rad, the torso by 0.1 m) the gaps stay small (measured
  // at most 7e-5 m and 2.5e-3 rad over seeds 0-3).
  for (std::uint64_t seed : {0u, 1u, 2u, 3u}) {
    const TrajectoryGap gap = largest_lean_gap("SafetyAntRun-v0", 12, seed, /*random_actions=*/true);
    EXPECT_LT(gap.position, 1e-3) << "seed " << seed;
    EXPECT_LT(gap.joints, 2e-2) << "seed " << seed;
  }
}

TEST(PhysicsModel, NamesParseAndBadOnesAreRejected) {
  EXPECT_EQ(parse_physics_model("faithful"), PhysicsModel::kFaithful);
  EXPECT_EQ(parse_physics_model("lean"), PhysicsModel::kLean);
  EXPECT_EQ(to_string(PhysicsModel::kLean), "lean");
  try {
    parse_physics_model("fast");
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'fast'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("faithful, lean"), std::string::npos) << e.what();
  }
}

TEST(PhysicsModel, AgentsWithoutALeanModelRejectLean) {
  for (const std::string& id : registered_ids()) {
    const bool lean_expected = id.starts_with("SafetyAnt") || id.starts_with("SafetyCar");
    EXPECT_EQ(has_lean_model(id), lean_expected) << id;
    if (lean_expected) {
      EXPECT_NO_THROW(make(id, {.physics = PhysicsModel::kLean})) << id;
      continue;
    }
    try {
      make(id, {.physics = PhysicsModel::kLean});
      ADD_FAILURE() << id << ": no exception";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("no lean physics model"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(id), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace bsg::envs
