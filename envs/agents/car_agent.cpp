#include "envs/agents/car_agent.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include <BulletCollision/CollisionShapes/btBoxShape.h>
#include <BulletCollision/CollisionShapes/btCompoundShape.h>
#include <BulletCollision/CollisionShapes/btConvexHullShape.h>
#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <BulletDynamics/Featherstone/btMultiBodyDynamicsWorld.h>
#include <BulletDynamics/Featherstone/btMultiBodyGearConstraint.h>
#include <BulletDynamics/Featherstone/btMultiBodyJointLimitConstraint.h>
#include <BulletDynamics/Featherstone/btMultiBodyJointMotor.h>
#include <BulletDynamics/Featherstone/btMultiBodyLinkCollider.h>

#include "envs/physics/orientation.h"
#include "envs/physics/rigid_body_merge.h"
#include "envs/physics/world.h"

namespace bsg::envs {
namespace {

// The model is `racecar_differential.urdf` of the original package with
// globalScaling = 3 (docs/environments.md#car). Lengths below are the URDF's own numbers and
// are multiplied by kUrdfScale exactly as PyBullet's URDF parser does, so that
// every frame matches the original to the last bit; masses are not scaled.
constexpr double kUrdfScale = 3.0;
// URDF importer's collision margin for boxes, convex hulls and the compound
// that wraps a link's shapes (docs/environments.md#how-bodies-are-built).
constexpr double kMargin = 0.001;
// Angles as written in the URDF (not π/2: the file says 1.5708 and 1.570795).
constexpr double kWheelRoll = 1.5708;
constexpr double kHingePitch = 1.5708;
constexpr double kDiffAngle = 1.570795;

enum class JointKind { kRevolute, kFixed };
enum class Geometry { kNone, kCylinder, kBox };

struct LinkSpec {
  const char* name;
  int parent;  // -1 = chassis (base)
  JointKind joint;
  btVector3 origin_xyz;  // joint origin in the parent link frame (unscaled)
  btVector3 origin_rpy;
  btVector3 axis;  // child frame, passed un-normalised (docs/environments.md#how-bodies-are-built)
  // Joint limits [−1, 1] are stored on both steering hinges, so both clamp
  // their position-motor targets (docs/environments.md#car). Only the left hinge
  // is a URDF "revolute" joint, and PyBullet's importer gives only revolute
  // joints a btMultiBodyJointLimitConstraint; the right hinge is "continuous"
  // and has none. The golden trajectories confirm it: with a limit constraint
  // on the right hinge too, the differential's spider gears leave the recorded
  // states by 3e-4 rad/s in the first step (1e-11 without).
  bool limited;
  bool limit_constraint;
  double mass_kg;
  btVector3 com_xyz;  // inertial origin in the link frame (unscaled)
  Geometry geometry;
  btVector3 geometry_xyz;  // collision origin (unscaled)
  btVector3 geometry_rpy;
  btVector3 size;  // cylinder: (radius, length, 0); box: full extents (unscaled)
  double friction;
  bool soft_contact;  // <contact><stiffness 300000/><damping 1000/>
};

const btVector3 kZero(0, 0, 0);
const btVector3 kWheel(0.05, 0.045, 0);
const btVector3 kSpider(0.015, 0.01, 0);
const btVector3 kRing(0.025, 0.01, 0);

// PyBullet link order (depth-first over the URDF tree, docs/environments.md#car),
// one link per two lines: the joint, then the inertial, collision and contact fields.
// clang-format off
const LinkSpec kLinks[CarAgent::kLinkCount] = {
  // name,                    parent, joint,                origin_xyz,          origin_rpy,          axis,       limited, limit_constraint,
  // mass_kg, com_xyz,         geometry,            geometry_xyz,    geometry_rpy,        size,                  friction, soft_contact
    {"left_steering_hinge",   -1,     JointKind::kRevolute, {0.325, 0.1, 0},     {0, kHingePitch, 0}, {-1, 0, 0}, true,    true,
     0.1,     kZero,           Geometry::kNone,     kZero,           kZero,               kZero,                 0.5,      false},
    {"left_front_wheel",      0,      JointKind::kRevolute, kZero,               {kWheelRoll, 0, 0},  {0, 0, -1}, false,   false,
     0.34055, {0, 0, -0.0225}, Geometry::kCylinder, {0, 0, -0.0225}, kZero,               kWheel,                1.1,      true},
    {"right_steering_hinge",  -1,     JointKind::kRevolute, {0.325, -0.1, 0},    {0, kHingePitch, 0}, {-1, 0, 0}, true,    false,
     0.1,     kZero,           Geometry::kNone,     kZero,           kZero,               kZero,                 0.5,      false},
    {"right_front_wheel",     2,      JointKind::kRevolute, kZero,               {kWheelRoll, 0, 0},  {0, 0, -1}, false,   false,
     0.34055, {0, 0, 0.0225},  Geometry::kCylinder, {0, 0, 0.0225},  kZero,               kWheel,                1.1,      true},
    {"laser",                 -1,     JointKind::kFixed,    {0.265, 0.0, 0.075}, kZero,               kZero,      false,   false,
     0.130,   kZero,           Geometry::kBox,      kZero,           kZero,               {0.1, 0.1, 0.1},       0.5,      false},
    {"zed_camera_link",       -1,     JointKind::kFixed,    {0.390, 0, 0.04},    kZero,               kZero,      false,   false,
     0.1,     kZero,           Geometry::kBox,      kZero,           kZero,               {0.033, 0.175, 0.030}, 0.5,      false},
    {"camera_link",           5,      JointKind::kFixed,    {0, 0.06, 0},        kZero,               kZero,      false,   false,
     0.01,    kZero,           Geometry::kNone,     kZero,           kZero,               kZero,                 0.5,      false},
    {"zed_camera_right_link", 5,      JointKind::kFixed,    {0, -0.06, 0},       kZero,               kZero,      false,   false,
     0.01,    kZero,           Geometry::kNone,     kZero,           kZero,               kZero,                 0.5,      false},
    {"diff_ring",             -1,     JointKind::kRevolute, kZero,               kZero,               {0, 1, 0},  false,   false,
     0.0637,  kZero,           Geometry::kCylinder, {0, 0.025, 0},   {kDiffAngle, 0, 0},  kRing,                 1.0,      true},
    {"diff_spiderA",          8,      JointKind::kRevolute, kZero,               {0, 0, kDiffAngle},  {0, 1, 0},  false,   false,
     0.056,   kZero,           Geometry::kCylinder, {0, 0.01, 0},    {kDiffAngle, 0, 0},  kSpider,               1.0,      true},
    {"diff_spiderB",          8,      JointKind::kRevolute, kZero,               {0, 0, -kDiffAngle}, {0, 1, 0},  false,   false,
     0.056,   kZero,           Geometry::kCylinder, {0, 0.01, 0},    {kDiffAngle, 0, 0},  kSpider,               1.0,      true},
    {"diff_sideA",            8,      JointKind::kRevolute, kZero,               kZero,               {0, 1, 0},  false,   false,
     0.056,   kZero,           Geometry::kCylinder, {0, 0.01, 0},    {kDiffAngle, 0, 0},  kSpider,               1.0,      true},
    {"left_rear_wheel",       11,     JointKind::kFixed,    {0, 0.1, 0},         {kWheelRoll, 0, 0},  kZero,      false,   false,
     0.34055, {0, 0, -0.0225}, Geometry::kCylinder, {0, 0, -0.0225}, kZero,               kWheel,                0.7,      true},
    {"diff_sideB",            8,      JointKind::kRevolute, kZero,               kZero,               {0, 1, 0},  false,   false,
     0.056,   kZero,           Geometry::kCylinder, {0, -0.01, 0},   {-kDiffAngle, 0, 0}, kSpider,               1.0,      true},
    {"right_rear_wheel",      13,     JointKind::kFixed,    {0, -0.1, 0},        {kWheelRoll, 0, 0},  kZero,      false,   false,
     0.34055, {0, 0, 0.0225},  Geometry::kCylinder, {0, 0, 0.0225},  kZero,               kWheel,                0.7,      true},
    {"diff2_ring",            -1,     JointKind::kRevolute, {0.32, 0.0, 0.0},    kZero,               {0, 1, 0},  false,   false,
     0.0637,  kZero,           Geometry::kCylinder, {0, 0.025, 0},   {kDiffAngle, 0, 0},  kRing,                 1.0,      true},
    {"diff2_spiderA",         15,     JointKind::kRevolute, kZero,               {0, 0, kDiffAngle},  {0, 1, 0},  false,   false,
     0.056,   kZero,           Geometry::kCylinder, {0, 0.01, 0},    {kDiffAngle, 0, 0},  kSpider,               1.0,      true},
    {"diff2_spiderB",         15,     JointKind::kRevolute, kZero,               {0, 0, -kDiffAngle}, {0, 1, 0},  false,   false,
     0.056,   kZero,           Geometry::kCylinder, {0, 0.01, 0},    {kDiffAngle, 0, 0},  kSpider,               1.0,      true},
    {"diff2_sideA",           15,     JointKind::kRevolute, kZero,               kZero,               {0, 1, 0},  false,   false,
     0.056,   kZero,           Geometry::kCylinder, {0, 0.01, 0},    {kDiffAngle, 0, 0},  kSpider,               1.0,      true},
    {"diff2_sideB",           15,     JointKind::kRevolute, kZero,               kZero,               {0, 1, 0},  false,   false,
     0.056,   kZero,           Geometry::kCylinder, {0, -0.01, 0},   {-kDiffAngle, 0, 0}, kSpider,               1.0,      true},
};
// clang-format on

// Chassis (base link): mass 4 kg, COM 0.2 (×3) ahead of the link frame. Its
// collision mesh (chassis_differential.STL) is replaced by the convex hull of
// its bounding box, x ∈ [−0.04, 0.365], |y| ≤ 0.1, |z| ≤ 0.03 (unscaled), the
// approximation of docs/environments.md#car; the hull's bounding box, hence the inertia
// (0.133944, 0.508479, 0.619359), is the mesh's.
constexpr double kChassisMassKg = 4.0;
const btVector3 kChassisCom(0.2, 0, 0);
const btVector3 kChassisMin(-0.04, -0.1, -0.03);
const btVector3 kChassisMax(0.365, 0.1, 0.03);
constexpr double kChassisFriction = 0.5;

// <contact> stiffness and damping of the wheels and differential parts.
constexpr double kContactStiffness = 300000;
constexpr double kContactDamping = 1000;
constexpr double kSteeringLimitRad = 1.0;

// Gear constraints: (linkA, linkB, ratio, aux link), in the original's
// creation order (docs/environments.md#car).
struct GearSpec {
  int link_a;
  int link_b;
  double ratio;
  int aux_link;
};
constexpr GearSpec kGears[] = {
    {9, 11, 1, -1},   {10, 13, -1, -1}, {9, 13, -1, -1}, {16, 18, 1, -1},
    {16, 19, -1, -1}, {17, 19, -1, -1}, {1, 18, -1, 15}, {3, 19, -1, 15},
};
constexpr double kGearMaxForce = 10000;

// Motor constants (docs/environments.md#motors-forces-and-contacts, #car). T_param (the environment
// step, World::env_step_seconds) bounds motor impulses whatever the number of
// sub-steps (PyBullet quirk, docs/environments.md#kept-quirks, item 1).
constexpr double kSteeringPerAction = 0.5;  // [rad]
constexpr double kSteeringKp = 0.1;
constexpr double kSteeringKd = 1.0;
constexpr double kSteeringForce = 100000;
constexpr double kWheelKd = 1.0;
constexpr double kSpeedPerAction = 40, kSpeedPerActionUpgraded = 80;  // [rad/s]
constexpr double kRingForce = 20, kRingForceUpgraded = 40;
// Indices into kMovableLinks of the driven joints.
constexpr int kLeftHingeMotor = 0;   // link 0
constexpr int kRightHingeMotor = 2;  // link 2
constexpr int kRearRingMotor = 4;    // link 8
constexpr int kFrontRingMotor = 9;   // link 15

btVector3 scaled(const btVector3& v) { return v * kUrdfScale; }

// A URDF <origin xyz rpy>: position scaled, rotation from PyBullet's Euler
// formula (the URDF parser uses the same one).
btTransform urdf_origin(const btVector3& xyz, const btVector3& rpy) {
  btTransform transform;
  transform.setIdentity();
  transform.setOrigin(scaled(xyz));
  if (!rpy.isZero()) transform.setRotation(quaternion_from_euler(rpy.x(), rpy.y(), rpy.z()));
  return transform;
}

btTransform translation(const btVector3& xyz) {
  btTransform transform;
  transform.setIdentity();
  transform.setOrigin(xyz);
  return transform;
}

// A URDF <cylinder>: a 32-gon prism as a convex hull (docs/environments.md#how-bodies-are-built),
// built as PyBullet's importer does (margin, AABB, then vertex optimisation).
std::unique_ptr<btConvexHullShape> cylinder_hull(double radius, double length) {
  const double half_length = 0.5 * length;
  constexpr int kSteps = 32;
  std::vector<btVector3> vertices;
  for (int i = 0; i < kSteps; ++i) {
    // float(i) / numSteps as in the importer (exact for 32 steps).
    const double angle = SIMD_2_PI * (static_cast<float>(i) / kSteps);
    btVector3 vertex(radius * std::sin(angle), radius * std::cos(angle), half_length);
    vertices.push_back(vertex);
    vertex[2] = -half_length;
    vertices.push_back(vertex);
  }
  auto hull = std::make_unique<btConvexHullShape>(
      &vertices[0].x(), static_cast<int>(vertices.size()), sizeof(btVector3));
  hull->setMargin(kMargin);
  hull->recalcLocalAabb();
  hull->optimizeConvexHull();
  return hull;
}

std::unique_ptr<btConvexHullShape> chassis_hull() {
  std::vector<btVector3> corners;
  for (int i = 0; i < 8; ++i) {
    corners.emplace_back(scaled(btVector3((i & 1) ? kChassisMax.x() : kChassisMin.x(),
                                          (i & 2) ? kChassisMax.y() : kChassisMin.y(),
                                          (i & 4) ? kChassisMax.z() : kChassisMin.z())));
  }
  // Mesh path of the importer: optimise, then margin, then AABB.
  auto hull = std::make_unique<btConvexHullShape>(&corners[0].x(), static_cast<int>(corners.size()),
                                                  sizeof(btVector3));
  hull->optimizeConvexHull();
  hull->setMargin(kMargin);
  hull->recalcLocalAabb();
  return hull;
}

// The link's collision shape as PyBullet's importer makes it: a compound with
// margin 0.001 holding the geometry at inertial⁻¹·origin, replaced by the
// geometry itself when that transform is the identity. Links without geometry
// keep the empty compound (it still yields a tiny inertia and a collider).
btCollisionShape* link_shape(World& world, const LinkSpec& spec) {
  auto compound = std::make_unique<btCompoundShape>();
  compound->setMargin(kMargin);
  if (spec.geometry == Geometry::kNone) return world.keep_shape(std::move(compound));

  std::unique_ptr<btCollisionShape> geometry;
  if (spec.geometry == Geometry::kCylinder) {
    geometry = cylinder_hull(kUrdfScale * spec.size.x(), kUrdfScale * spec.size.y());
  } else {
    auto box = std::make_unique<btBoxShape>(scaled(spec.size) * 0.5f);
    box->setMargin(kMargin);
    geometry = std::move(box);
  }
  const btTransform child = translation(scaled(spec.com_xyz)).inverse() *
                            urdf_origin(spec.geometry_xyz, spec.geometry_rpy);
  if (child == btTransform::getIdentity()) return world.keep_shape(std::move(geometry));
  btCollisionShape* kept_geometry = world.keep_shape(std::move(geometry));
  compound->addChildShape(child, kept_geometry);
  return world.keep_shape(std::move(compound));
}

// True for the links the lean model welds into the base: their joint, and
// every joint between them and the chassis, is fixed.
bool welded_into_base(int link) {
  for (int i = link; i >= 0; i = kLinks[i].parent) {
    if (kLinks[i].joint != JointKind::kFixed) return false;
  }
  return true;
}

}  // namespace

CarAgent::CarAgent(World& world, const AgentOptions& options)
    : speed_per_action_rad_per_s_(options.power_upgrade ? kSpeedPerActionUpgraded
                                                        : kSpeedPerAction),
      ring_motor_max_impulse_((options.power_upgrade ? kRingForceUpgraded : kRingForce) *
                              world.env_step_seconds()),
      steering_max_impulse_(kSteeringForce * world.env_step_seconds()),
      clip_actions_(options.clip_actions) {
  traits_.action_dim = 2;
  traits_.observation_dim = 7;
  traits_.initial_position = btVector3(0, 0, 0.2);
  traits_.initial_yaw = std::numbers::pi;
  traits_.collision_radius = 0.35;
  traits_.run_speed_limit = 1.5;
  traits_.sensor_rotates = true;
  traits_.sensor_offset = btVector3(0.2, 0, 0.3);
  if (options.physics == PhysicsModel::kLean) {
    build_lean(world);
  } else {
    build_faithful(world);
  }
}

// The shapes and inertias both models start from: the chassis hull, and the
// links' shapes with inertias from them, not from the URDF
// (docs/environments.md#how-bodies-are-built).
CarAgent::CarShapes CarAgent::make_shapes(World& world) {
  CarShapes shapes;
  // The chassis compound holds the hull at −COM (inertial frame at COM).
  shapes.chassis_inertial = translation(scaled(kChassisCom));
  shapes.hull = world.keep_shape(chassis_hull());
  auto chassis = std::make_unique<btCompoundShape>();
  chassis->setMargin(kMargin);
  chassis->addChildShape(shapes.chassis_inertial.inverse(), shapes.hull);
  shapes.chassis = world.keep_shape(std::move(chassis));
  shapes.chassis->calculateLocalInertia(kChassisMassKg, shapes.chassis_inertia);
  for (int i = 0; i < kLinkCount; ++i) {
    shapes.links[i] = link_shape(world, kLinks[i]);
    shapes.inertias[i].setZero();
    shapes.links[i]->calculateLocalInertia(kLinks[i].mass_kg, shapes.inertias[i]);
  }
  return shapes;
}

// Every PyBullet link is a body link; the base is the chassis alone.
void CarAgent::build_faithful(World& world) {
  const CarShapes shapes = make_shapes(world);
  welded_base_ = false;
  BodyLinks body_link{};
  for (int i = 0; i < kLinkCount; ++i) {
    body_link[i] = i;
    link_places_[i] = {body_link[i], btTransform::getIdentity()};
  }
  const CarBase base{kChassisMassKg, shapes.chassis_inertia, shapes.chassis_inertial, shapes.chassis};
  assemble(world, shapes, base, body_link, kLinkCount);
}

// The links joined to the chassis by fixed joints are welded into the base
// (envs/physics/rigid_body_merge.h); the others stay body links.
void CarAgent::build_lean(World& world) {
  const CarShapes shapes = make_shapes(world);
  welded_base_ = true;
  BodyLinks body_link{};  // −1: welded into the base
  int body_link_count = 0;
  for (int i = 0; i < kLinkCount; ++i) {
    body_link[i] = welded_into_base(i) ? -1 : body_link_count++;
    link_places_[i] = {body_link[i], btTransform::getIdentity()};
  }
  const CarBase base = weld_into_base(world, shapes, body_link);
  assemble(world, shapes, base, body_link, body_link_count);
}

// The lean base: mass, principal inertia and COM frame of the chassis and the
// welded links, and one compound of their shapes. Sets the welded links'
// places and the chassis's frame in the base.
CarAgent::CarBase CarAgent::weld_into_base(World& world, const CarShapes& shapes, const BodyLinks& body_link) {
  // COM frames of the welded links in the chassis link frame (URDF chain).
  std::array<btTransform, kLinkCount> link_frame{};
  std::array<btTransform, kLinkCount> com_frame{};
  std::vector<RigidPart> parts = {
      {kChassisMassKg, shapes.chassis_inertia, shapes.chassis_inertial.getOrigin(), btQuaternion::getIdentity()}};
  for (int i = 0; i < kLinkCount; ++i) {
    if (body_link[i] >= 0) continue;
    const LinkSpec& spec = kLinks[i];
    const btTransform parent_frame =
        spec.parent < 0 ? btTransform::getIdentity() : link_frame[spec.parent];
    link_frame[i] = parent_frame * urdf_origin(spec.origin_xyz, spec.origin_rpy);
    com_frame[i] = link_frame[i] * translation(scaled(spec.com_xyz));
    parts.push_back({spec.mass_kg, shapes.inertias[i], com_frame[i].getOrigin(), com_frame[i].getRotation()});
  }
  const MergedBody merged = merge_rigid_parts(parts);
  // The laser and the cameras sit above and ahead of the chassis COM, so the
  // merged inertia has a product I_xz; btMultiBody takes a diagonal base
  // inertia, so the base's COM frame is the merged body's principal frame
  // (turned about y by a small angle; the y products vanish by symmetry).
  btMatrix3x3 principal = merged.inertia;
  btMatrix3x3 axes;
  principal.diagonalize(axes, SIMD_EPSILON, 32);
  const double trace = principal[0][0] + principal[1][1] + principal[2][2];
  const double off_diagonal = std::max(
      {std::abs(principal[0][1]), std::abs(principal[0][2]), std::abs(principal[1][2])});
  if (!(off_diagonal <= 1e-14 * trace) || axes.determinant() < 0) {
    throw std::logic_error("CarAgent: the lean base's inertia has no principal frame");
  }
  CarBase base;
  base.mass = merged.mass;
  base.inertia = btVector3(principal[0][0], principal[1][1], principal[2][2]);
  base.inertial = btTransform(axes, merged.com);
  chassis_in_base_ = base.inertial.inverse() * shapes.chassis_inertial;
  // One compound: the chassis hull and the welded links' geometry where the
  // faithful links put them (the shapes are expressed in the link COM frames).
  auto compound = std::make_unique<btCompoundShape>();
  compound->setMargin(kMargin);
  compound->addChildShape(base.inertial.inverse(), shapes.hull);
  for (int i = 0; i < kLinkCount; ++i) {
    if (body_link[i] >= 0) continue;
    link_places_[i].offset = base.inertial.inverse() * com_frame[i];
    if (kLinks[i].geometry != Geometry::kNone) {
      compound->addChildShape(link_places_[i].offset, shapes.links[i]);
    }
  }
  base.shape = world.keep_shape(std::move(compound));
  return base;
}

// The multibody on `base` with the body links, its colliders and constraints,
// added to the world (both models).
void CarAgent::assemble(World& world, const CarShapes& shapes, const CarBase& base, const BodyLinks& body_link,
                        int body_link_count) {
  auto body = std::make_unique<btMultiBody>(body_link_count, base.mass, base.inertia,
                                            /*fixedBase=*/false, /*canSleep=*/false);
  set_up_joints(*body, shapes, base, body_link);
  add_colliders(world, *body, shapes, base, body_link);
  body->setHasSelfCollision(false);
  body->finalizeMultiDof();
  body_ = world.add_multibody(std::move(body));
  for (int m = 0; m < kMovableJointCount; ++m) movable_links_[m] = body_link[kMovableLinks[m]];
  set_base_pose(traits_.initial_position, quaternion_from_euler(0, 0, traits_.initial_yaw));
  add_constraints(world, body_link);
}

// Joint frames exactly as URDF2Bullet computes them.
void CarAgent::set_up_joints(btMultiBody& mb, const CarShapes& shapes, const CarBase& base,
                             const BodyLinks& body_link) {
  for (int i = 0; i < kLinkCount; ++i) {
    if (body_link[i] < 0) continue;
    const LinkSpec& spec = kLinks[i];
    const int parent = spec.parent < 0 ? -1 : body_link[spec.parent];
    if (spec.parent >= 0 && parent < 0) {
      throw std::logic_error("CarAgent: a moving link hangs from a welded one");
    }
    const btTransform parent_inertial =
        spec.parent < 0 ? base.inertial : translation(scaled(kLinks[spec.parent].com_xyz));
    const btTransform local_inertial = translation(scaled(spec.com_xyz));
    const btTransform parent_to_joint = urdf_origin(spec.origin_xyz, spec.origin_rpy);
    const btTransform offset_in_a = parent_inertial.inverse() * parent_to_joint;
    const btTransform offset_in_b = local_inertial.inverse();
    const btQuaternion parent_rot_to_this =
        offset_in_b.getRotation() * offset_in_a.inverse().getRotation();
    const int link = body_link[i];
    if (spec.joint == JointKind::kRevolute) {
      mb.setupRevolute(link, spec.mass_kg, shapes.inertias[i], parent, parent_rot_to_this,
                       quatRotate(offset_in_b.getRotation(), spec.axis), offset_in_a.getOrigin(),
                       -offset_in_b.getOrigin(), /*disableParentCollision=*/true);
      if (spec.limited) {
        mb.getLink(link).m_jointLowerLimit = -kSteeringLimitRad;
        mb.getLink(link).m_jointUpperLimit = kSteeringLimitRad;
      }
    } else {
      mb.setupFixed(link, spec.mass_kg, shapes.inertias[i], parent, parent_rot_to_this,
                    offset_in_a.getOrigin(), -offset_in_b.getOrigin());
    }
  }
}

// Colliders in PyBullet's creation order: base, then links 0..19.
// No self collision (docs/environments.md#how-bodies-are-built).
void CarAgent::add_colliders(World& world, btMultiBody& mb, const CarShapes& shapes, const CarBase& base,
                             const BodyLinks& body_link) {
  auto add_collider = [&](int link, btCollisionShape* shape, double friction, bool soft) {
    auto collider = std::make_unique<btMultiBodyLinkCollider>(&mb, link);
    collider->setCollisionShape(shape);
    collider->setFriction(friction);
    collider->setRollingFriction(0);
    if (soft) collider->setContactStiffnessAndDamping(kContactStiffness, kContactDamping);
    btMultiBodyLinkCollider* added = world.add_collider(std::move(collider));
    if (link < 0) {
      mb.setBaseCollider(added);
    } else {
      mb.getLink(link).m_collider = added;
    }
    colliders_.push_back(added);
  };
  // The welded links' friction (0.5) and hard contacts are the chassis's.
  add_collider(-1, base.shape, kChassisFriction, false);
  for (int i = 0; i < kLinkCount; ++i) {
    if (body_link[i] >= 0) add_collider(body_link[i], shapes.links[i], kLinks[i].friction, kLinks[i].soft_contact);
  }
}

// Constraints in PyBullet's order: joint limits (importer), one motor per
// revolute joint (createJointMotors), then the gears (the agent's code).
void CarAgent::add_constraints(World& world, const BodyLinks& body_link) {
  for (int i = 0; i < kLinkCount; ++i) {
    if (kLinks[i].limit_constraint) {
      const btMultibodyLink& link = body_->getLink(body_link[i]);
      world.add_constraint(std::make_unique<btMultiBodyJointLimitConstraint>(
          body_, body_link[i], link.m_jointLowerLimit, link.m_jointUpperLimit));
    }
  }
  for (int m = 0; m < kMovableJointCount; ++m) {
    // The lean model keeps the 10 motors that are never switched on. They make
    // no solver row (Bullet skips a motor whose max impulse is 0), so leaving
    // them out saves under 1 % of the instructions; but Bullet quick-sorts the
    // constraint array each step (not a stable sort), and without them the
    // gear rows are solved in another order: the differentials' spider gears
    // then part from the faithful model by ~20 rad/s in the first step.
    auto motor = std::make_unique<btMultiBodyJointMotor>(body_, movable_links_[m], 0,
                                                         /*desiredVelocity=*/0.0,
                                                         /*maxMotorImpulse=*/1.0);
    motor->setPositionTarget(0, 0);
    motor->setVelocityTarget(0, 1);
    motor->finalizeMultiDof();
    // The agent's constructor switches every motor off (force 0, docs/environments.md#motors-forces-and-contacts).
    motor->setMaxAppliedImpulse(0);
    motors_[m] = static_cast<btMultiBodyJointMotor*>(world.add_constraint(std::move(motor)));
  }
  const double gear_max_impulse = kGearMaxForce * world.internal_step_seconds();  // F·h, docs/environments.md#motors-forces-and-contacts
  const btMatrix3x3 identity = btMatrix3x3::getIdentity();
  for (const GearSpec& gear : kGears) {
    auto constraint = std::make_unique<btMultiBodyGearConstraint>(
        body_, body_link[gear.link_a], body_, body_link[gear.link_b], btVector3(0, 0, 0),
        btVector3(0, 0, 0), identity, identity);
    constraint->setGearRatio(gear.ratio);
    if (gear.aux_link >= 0) constraint->setGearAuxLink(body_link[gear.aux_link]);
    constraint->setMaxAppliedImpulse(gear_max_impulse);
    world.add_constraint(std::move(constraint));
  }
}

void CarAgent::refresh_colliders() {
  body_->forwardKinematics(scratch_rotations_, scratch_vectors_);
  body_->updateCollisionObjectWorldTransforms(scratch_rotations_, scratch_vectors_);
}

btTransform CarAgent::chassis_com_transform() const {
  if (!welded_base_) return body_->getBaseWorldTransform();
  return body_->getBaseWorldTransform() * chassis_in_base_;
}

void CarAgent::reset(Rng& rng) {
  body_->setBaseVel(btVector3(0, 0, 0));
  body_->setBaseOmega(btVector3(0, 0, 0));
  set_base_pose(traits_.initial_position, quaternion_from_euler(0, 0, traits_.initial_yaw));
  // 14 draws, one per movable joint in order (docs/environments.md#car).
  std::array<double, kMovableJointCount> angles{};
  for (double& angle : angles) angle = uniform(rng, -0.1, 0.1);
  set_joint_positions(angles);
}

void CarAgent::set_base_pose(const btVector3& com_position, const btQuaternion& orientation) {
  // PyBullet's resetBasePositionAndOrientation goes through a btTransform
  // (quaternion → matrix → quaternion), which we reproduce.
  btTransform transform;
  transform.setIdentity();
  transform.setOrigin(com_position);
  transform.setRotation(orientation);
  // Lean: the pose given is the chassis COM's; the base's COM frame follows it.
  if (welded_base_) transform = transform * chassis_in_base_.inverse();
  body_->setBaseWorldTransform(transform);
  refresh_colliders();
}

void CarAgent::set_joint_positions(std::span<const double> joint_positions) {
  if (joint_positions.size() != kMovableJointCount) {
    throw std::invalid_argument("CarAgent::set_joint_positions: expected " +
                                std::to_string(kMovableJointCount) + " joint angles, got " +
                                std::to_string(joint_positions.size()));
  }
  for (int m = 0; m < kMovableJointCount; ++m) {
    body_->setJointPos(movable_links_[m], joint_positions[m]);
    body_->setJointVel(movable_links_[m], 0);
  }
  refresh_colliders();
}

void CarAgent::apply_action(std::span<const double> action) {
  if (action.size() != 2) {
    throw std::invalid_argument("CarAgent::apply_action: expected 2 action entries, got " +
                                std::to_string(action.size()));
  }
  // Not clipped (docs/environments.md#kept-quirks, item 4), unless the description
  // asks for the fork's clipping (clip_actions).
  const double throttle = clip_actions_ ? std::clamp(action[0], -1.0, 1.0) : action[0];
  const double steering = clip_actions_ ? std::clamp(action[1], -1.0, 1.0) : action[1];
  wheel_target_rad_per_s_ = speed_per_action_rad_per_s_ * throttle;
  for (int m : {kRearRingMotor, kFrontRingMotor}) {
    // VELOCITY_CONTROL: kd 1, kp 0, no rhs clamp, impulse F·T_param (docs/environments.md#motors-forces-and-contacts).
    btMultiBodyJointMotor& motor = *motors_[m];
    motor.setVelocityTarget(wheel_target_rad_per_s_, kWheelKd);
    motor.setPositionTarget(0, 0);
    motor.setRhsClamp(SIMD_INFINITY);
    motor.setMaxAppliedImpulse(ring_motor_max_impulse_);
  }
  const double steering_rad = kSteeringPerAction * steering;
  for (int m : {kLeftHingeMotor, kRightHingeMotor}) {
    // POSITION_CONTROL with PyBullet's defaults; the target is clamped to the
    // hinge limits (both hinges are limited, docs/environments.md#car).
    const btMultibodyLink& link = body_->getLink(movable_links_[m]);
    const double target = std::clamp(steering_rad, link.m_jointLowerLimit, link.m_jointUpperLimit);
    btMultiBodyJointMotor& motor = *motors_[m];
    motor.setVelocityTarget(0, kSteeringKd);
    motor.setPositionTarget(target, kSteeringKp);
    motor.setMaxAppliedImpulse(steering_max_impulse_);
    steering_target_rad_ = target;
  }
}

void CarAgent::write_observation(std::span<double> out) const {
  if (out.size() != 7) {
    throw std::invalid_argument("CarAgent::write_observation: expected 7 entries, got " +
                                std::to_string(out.size()));
  }
  // [0.1·x, 0.1·y, v_x, v_y, sin ψ, cos ψ, 0.1·ω_z] (docs/environments.md#car).
  const btVector3 p = position();
  const btVector3 v = linear_velocity();
  const double yaw = euler_from_quaternion(orientation()).yaw;
  out[0] = 0.1 * p.x();
  out[1] = 0.1 * p.y();
  out[2] = v.x();
  out[3] = v.y();
  out[4] = std::sin(yaw);
  out[5] = std::cos(yaw);
  out[6] = 0.1 * angular_velocity().z();
}

btVector3 CarAgent::position() const {
  if (!welded_base_) return body_->getBasePos();
  return chassis_com_transform().getOrigin();
}

btQuaternion CarAgent::orientation() const {
  // As PyBullet reports it: from the base world transform (matrix → quaternion).
  return chassis_com_transform().getRotation();
}

btVector3 CarAgent::linear_velocity() const {
  if (!welded_base_) return body_->getBaseVel();
  // The chassis COM's velocity on the welded base: v + ω × r.
  const btVector3 r = body_->getBaseWorldTransform().getBasis() * chassis_in_base_.getOrigin();
  return body_->getBaseVel() + body_->getBaseOmega().cross(r);
}

btVector3 CarAgent::angular_velocity() const { return body_->getBaseOmega(); }

void CarAgent::joint_state(std::span<double> positions, std::span<double> velocities) const {
  if (positions.size() != kMovableJointCount || velocities.size() != kMovableJointCount) {
    throw std::invalid_argument("CarAgent::joint_state: expected spans of " +
                                std::to_string(kMovableJointCount) + " entries");
  }
  for (int m = 0; m < kMovableJointCount; ++m) {
    positions[m] = body_->getJointPos(movable_links_[m]);
    velocities[m] = body_->getJointVel(movable_links_[m]);
  }
}

btTransform CarAgent::link_com_transform(int link) const {
  if (link < 0 || link >= kLinkCount) {
    throw std::out_of_range("CarAgent::link_com_transform: link " + std::to_string(link) +
                            " outside [0, " + std::to_string(kLinkCount) + ")");
  }
  const LinkPlace& place = link_places_[link];
  if (place.body_link >= 0) return body_->getLink(place.body_link).m_cachedWorldTransform;
  return body_->getBaseWorldTransform() * place.offset;
}

std::unique_ptr<Agent> make_car_agent(World& world, const AgentOptions& options) {
  return std::make_unique<CarAgent>(world, options);
}

}  // namespace bsg::envs
