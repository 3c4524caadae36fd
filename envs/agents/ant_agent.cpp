#include "envs/agents/ant_agent.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include <BulletCollision/CollisionShapes/btCompoundShape.h>
#include <BulletCollision/CollisionShapes/btMultiSphereShape.h>
#include <BulletCollision/CollisionShapes/btSphereShape.h>
#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <BulletDynamics/Featherstone/btMultiBodyJointLimitConstraint.h>
#include <BulletDynamics/Featherstone/btMultiBodyJointMotor.h>
#include <BulletDynamics/Featherstone/btMultiBodyLinkCollider.h>

#include "envs/physics/rigid_body_merge.h"
#include "envs/physics/world.h"

namespace bsg::envs {
namespace {

// PyBullet's MJCF importer parses every number into a float before widening
// it to double, so the model's lengths are the float32 values of the MJCF's
// decimals (the golden link poses show 0.2 as 0.20000000298023224).
constexpr double kStubLength = static_cast<float>(0.2);  // leg stub and thigh: 0 → 0.2·u
constexpr double kFootLength = static_cast<float>(0.4);  // foot: 0 → 0.4·u
constexpr double kCapsuleRadius = static_cast<float>(0.08);
constexpr double kTorsoRadius = 0.25;  // sphere sizes are parsed as double
// The importer ignores the MJCF density and uses 1000 kg/m³ (docs/environments.md#how-bodies-are-built).
constexpr double kDensity = 1000;
constexpr double kFriction = 1.5;  // MJCF default geom friction (docs/environments.md#ant)

constexpr double kInitialHeight = 0.75;
constexpr double kAliveHeight = 0.26;  // alive iff torso z > 0.26 (docs/environments.md#ant)
// Torque per unit action is power·power_coef: 2.5·100, or 10·100 with the upgrade.
constexpr double kTorqueScale = 100;
constexpr double kPower = 2.5;
constexpr double kUpgradedPower = 10;
// Reward factors (docs/environments.md#ant).
constexpr double kElectricityCost = -2.0;
constexpr double kStallTorqueCost = -0.1;
constexpr double kJointsAtLimitCost = -0.1;
constexpr float kAtLimitThreshold = 0.99f;  // NumPy compares the float32 ρ with float32(0.99)

// One leg: direction u = (s_x, s_y, 0) and the ankle axis, un-normalised (docs/environments.md#how-bodies-are-built).
struct LegGeometry {
  double sign_x;
  double sign_y;
  double ankle_axis_x;  // ankle axis (ankle_axis_x, 1, 0)
};
constexpr std::array<LegGeometry, 4> kLegs = {{
    {+1, +1, -1},  // front_left: hip_1, ankle_1 about (−1, 1, 0)
    {-1, +1, +1},  // front_right: hip_2, ankle_2 about (1, 1, 0)
    {-1, -1, -1},  // left_back: hip_3, ankle_3 about (−1, 1, 0)
    {+1, -1, +1},  // right_back: hip_4, ankle_4 about (1, 1, 0)
}};

// Joint limits are float32 values (docs/environments.md#ant), in action order.
constexpr double kHipLimit = 0.6981317400932312;
constexpr double kAnkleLow = 0.5235987901687622;
constexpr double kAnkleHigh = 1.7453292608261108;
struct JointLimits {
  double lower;
  double upper;
};
constexpr std::array<JointLimits, AntAgent::kActionDim> kLimits = {{
    {-kHipLimit, kHipLimit},
    {kAnkleLow, kAnkleHigh},
    {-kHipLimit, kHipLimit},
    {-kAnkleHigh, -kAnkleLow},
    {-kHipLimit, kHipLimit},
    {-kAnkleHigh, -kAnkleLow},
    {-kHipLimit, kHipLimit},
    {kAnkleLow, kAnkleHigh},
}};

// The importer's computeVolume, term by term in its order of evaluation.
double capsule_mass_kg(double length) {
  double volume = 4. / 3. * SIMD_PI * kCapsuleRadius * kCapsuleRadius * kCapsuleRadius;
  volume += SIMD_PI * kCapsuleRadius * kCapsuleRadius * length;
  return kDensity * volume;
}

double sphere_mass_kg(double radius) {
  return kDensity * (4. / 3. * SIMD_PI * radius * radius * radius);
}

// NumPy's pairwise sum of exactly 8 values (eight accumulators, then a tree),
// divided by 8: the original's float(np.mean(x)) bit for bit.
double numpy_mean8(const std::array<double, 8>& x) {
  return (((x[0] + x[1]) + (x[2] + x[3])) + ((x[4] + x[5]) + (x[6] + x[7]))) / 8.0;
}

// Half-span-normalised joint position ρ = 2(q − m)/(u − l) and the scaled
// rate 0.1·q̇, rounded to float32 as the original's float32 array does
// (docs/environments.md#ant).
float relative_position(double q, const JointLimits& limits) {
  const double mid = 0.5 * (limits.lower + limits.upper);
  return static_cast<float>(2 * (q - mid) / (limits.upper - limits.lower));
}
float scaled_rate(double qd) { return static_cast<float>(0.1 * qd); }

}  // namespace

// A capsule geom from 0 to `to` becomes a compound holding a two-sphere
// btMultiSphereShape (Bullet's default margin 0.04), shifted so that the
// link's inertial frame sits at the capsule's midpoint. Its inertia is
// Bullet's bounding-box estimate of that compound (docs/environments.md#how-bodies-are-built), which is
// what gives the table's (0.16394, 0.16394, 0.252698) for a stub.
AntAgent::CapsuleLink AntAgent::make_capsule(const btVector3& to) {
  const btVector3 from(0, 0, 0);
  const btVector3 centres[2] = {from, to};
  const btScalar radii[2] = {kCapsuleRadius, kCapsuleRadius};
  CapsuleLink link;
  link.spheres = world_.keep_shape(std::make_unique<btMultiSphereShape>(centres, radii, 2));
  auto compound = std::make_unique<btCompoundShape>();
  link.com_offset = 0.5 * (from + to);  // importer's inertialShift
  btTransform child;
  child.setIdentity();
  child.setOrigin(-link.com_offset);
  compound->addChildShape(child, link.spheres);
  link.shape = world_.keep_shape(std::move(compound));
  // The capsule's length is the norm of its float32 end point, as the importer computes it.
  link.mass = capsule_mass_kg(to.length());
  link.shape->calculateLocalInertia(link.mass, link.inertia);
  return link;
}

AntAgent::AntAgent(World& world, const AgentOptions& options)
    : world_(world),
      physics_(options.physics),
      torque_per_unit_action_((options.power_upgrade ? kUpgradedPower : kPower) * kTorqueScale) {
  traits_.action_dim = kActionDim;
  traits_.observation_dim = kObservationDim;
  traits_.initial_position = {0, 0, kInitialHeight};
  traits_.initial_yaw = 0;
  traits_.collision_radius = 0.25;
  traits_.run_speed_limit = 1.5;
  traits_.sensor_rotates = false;
  traits_.sensor_offset = {0, 0, 0};

  // Torso: a lone sphere, so its inertia is the sphere's 0.4·m·r² (docs/environments.md#ant).
  torso_shape_ = world.keep_shape(std::make_unique<btSphereShape>(kTorsoRadius));
  torso_mass_ = sphere_mass_kg(kTorsoRadius);
  torso_shape_->calculateLocalInertia(torso_mass_, torso_inertia_);
  for (int leg = 0; leg < 4; ++leg) {
    const LegGeometry& g = kLegs[leg];
    legs_[leg].stub = make_capsule(btVector3(g.sign_x * kStubLength, g.sign_y * kStubLength, 0));
    legs_[leg].thigh = make_capsule(btVector3(g.sign_x * kStubLength, g.sign_y * kStubLength, 0));
    legs_[leg].foot = make_capsule(btVector3(g.sign_x * kFootLength, g.sign_y * kFootLength, 0));
  }
  if (physics_ == PhysicsModel::kLean) {
    build_lean();
  } else {
    build_faithful();
  }
  set_base_pose(traits_.initial_position, btQuaternion::getIdentity());
}

btMultiBodyLinkCollider* AntAgent::add_collider(int link, btCollisionShape* shape) {
  auto collider = std::make_unique<btMultiBodyLinkCollider>(body_, link);
  collider->setCollisionShape(shape);
  collider->setFriction(kFriction);
  btMultiBodyLinkCollider* added = world_.add_collider(std::move(collider));
  if (link < 0) {
    body_->setBaseCollider(added);
  } else {
    body_->getLink(link).m_collider = added;
  }
  colliders_.push_back(added);
  return added;
}

void AntAgent::add_joint_limits() {
  // Hard limits on the 8 revolute joints (docs/environments.md#how-bodies-are-built), created in link
  // order as the importer does; Bullet's default max impulse (100) is kept.
  for (int k = 0; k < kActionDim; ++k) {
    const int link = movable_links_[k];
    body_->getLink(link).m_jointLowerLimit = kLimits[k].lower;
    body_->getLink(link).m_jointUpperLimit = kLimits[k].upper;
    world_.add_constraint(std::make_unique<btMultiBodyJointLimitConstraint>(
        body_, link, kLimits[k].lower, kLimits[k].upper));
  }
}

void AntAgent::build_faithful() {
  auto body = std::make_unique<btMultiBody>(kLinkCount, torso_mass_, torso_inertia_,
                                            /*fixedBase=*/false, /*canSleep=*/false);
  const btQuaternion no_rotation = btQuaternion::getIdentity();
  const btVector3 zero(0, 0, 0);
  std::array<btCollisionShape*, kLinkCount> link_shapes{};
  for (int leg = 0; leg < 4; ++leg) {
    const LegGeometry& g = kLegs[leg];
    const CapsuleLink& stub = legs_[leg].stub;
    const CapsuleLink& thigh = legs_[leg].thigh;
    const CapsuleLink& foot = legs_[leg].foot;
    const btVector3 stub_end(g.sign_x * kStubLength, g.sign_y * kStubLength, 0);
    const int first = 5 * leg;
    // Joint pivots are the child bodies' MJCF positions (0.2·u from the parent
    // body frame), expressed from the parent's COM as URDF2Bullet does.
    const btVector3 pivot_from_stub_com = stub_end - stub.com_offset;
    const btVector3 pivot_from_thigh_com = stub_end - thigh.com_offset;

    // <leg>: fixed to the torso at the torso centre.
    body->setupFixed(first, stub.mass, stub.inertia, -1, no_rotation, zero, stub.com_offset);
    // hip_k: a massless link carrying the joint about z.
    body->setupRevolute(first + 1, 0, zero, first, no_rotation, btVector3(0, 0, 1),
                        pivot_from_stub_com, zero, /*disableParentCollision=*/true);
    // aux_k (thigh): fixed to the hip link.
    body->setupFixed(first + 2, thigh.mass, thigh.inertia, first + 1, no_rotation, zero,
                     thigh.com_offset);
    // ankle_k: a massless link with the un-normalised axis passed as written.
    body->setupRevolute(first + 3, 0, zero, first + 2, no_rotation,
                        btVector3(g.ankle_axis_x, 1, 0),
                        pivot_from_thigh_com, zero, /*disableParentCollision=*/true);
    // <foot>: fixed to the ankle link.
    body->setupFixed(first + 4, foot.mass, foot.inertia, first + 3, no_rotation, zero,
                     foot.com_offset);
    link_shapes[first] = stub.shape;
    link_shapes[first + 2] = thigh.shape;
    link_shapes[first + 4] = foot.shape;
    // Every PyBullet link is a body link of its own.
    for (int i = 0; i < 5; ++i) link_places_[first + i] = {first + i, zero};
  }
  body->finalizeMultiDof();
  // The MJCF geoms never collide with each other (docs/environments.md#how-bodies-are-built).
  body->setHasSelfCollision(false);
  body_ = world_.add_multibody(std::move(body));
  std::copy(kMovableLinks.begin(), kMovableLinks.end(), movable_links_.begin());

  // Colliders in PyBullet's creation order: base, then links by index
  // (massless joint links have none).
  add_collider(-1, torso_shape_);
  for (int link = 0; link < kLinkCount; ++link) {
    if (link_shapes[link] == nullptr) continue;
    btMultiBodyLinkCollider* collider = add_collider(link, link_shapes[link]);
    const auto foot = std::find(kFootLinks.begin(), kFootLinks.end(), link);
    if (foot != kFootLinks.end()) feet_[foot - kFootLinks.begin()] = collider;
  }
  add_joint_limits();

  // PyBullet then gives every revolute joint a velocity motor
  // (createJointMotors), which the agent disables at construction with a
  // force-0 control call (max impulse 0, docs/environments.md#motors-forces-and-contacts). The disabled motors exert
  // nothing, but they are in the world's constraint array, and Bullet
  // quick-sorts that array by island each step (not a stable sort): without
  // them the joint-limit rows are solved in a different order and the
  // trajectory departs from the original as soon as two limits are active.
  for (const int link : kMovableLinks) {
    auto motor = std::make_unique<btMultiBodyJointMotor>(body_, link, 0, /*desiredVelocity=*/0.0,
                                                         /*maxMotorImpulse=*/1.0);
    motor->setPositionTarget(0, 0);
    motor->setVelocityTarget(0, 1);
    btMultiBodyConstraint* added = world_.add_constraint(std::move(motor));
    added->finalizeMultiDof();
    added->setMaxAppliedImpulse(0);
  }
}

void AntAgent::build_lean() {
  // The same bodies welded where the faithful model has fixed joints: the
  // torso and the four leg stubs are one base (the stubs' COMs sit
  // symmetrically about the torso centre, so the base COM stays there and the
  // products of inertia cancel); each massless hip link carries its thigh and
  // each massless ankle link its foot, exactly (a massless body adds nothing).
  // The disabled motors are left out: their max impulse is 0 for ever, and
  // Bullet makes no solver row for them.
  // One difference remains, below anything physical: Bullet's default
  // velocity damping (0.04) acts per body, as 0.04·(1 + |v|)·m·v and
  // 0.04·(1 + |ω|)·I·ω. Welding keeps its linear part exactly (equal
  // coefficients make the stubs' drag at their own COMs equal the welded
  // parallel-axis term), and the stubs' quadratic part, which cancels to first
  // order over the four symmetric stubs, moves by about 0.025·|ω|² N and
  // 0.025·|ω|·||v| − |ω|| N·m (SI units) beside a 950 N weight and 250 N·m
  // joint torques.
  std::array<RigidPart, 5> base_parts;
  base_parts[0] = {torso_mass_, torso_inertia_, btVector3(0, 0, 0), btQuaternion::getIdentity()};
  for (int leg = 0; leg < 4; ++leg) {
    const CapsuleLink& stub = legs_[leg].stub;
    base_parts[1 + leg] = {stub.mass, stub.inertia, stub.com_offset, btQuaternion::getIdentity()};
  }
  const MergedBody base = merge_rigid_parts(base_parts);
  const btMatrix3x3& inertia = base.inertia;
  if (!base.com.isZero() || inertia[0][1] != 0 || inertia[0][2] != 0 || inertia[1][2] != 0) {
    throw std::logic_error("AntAgent: the lean base is not symmetric about the torso centre");
  }
  const btVector3 base_inertia(inertia[0][0], inertia[1][1], inertia[2][2]);

  constexpr int kLeanLinkCount = 2 * 4;
  auto body = std::make_unique<btMultiBody>(kLeanLinkCount, base.mass, base_inertia,
                                            /*fixedBase=*/false, /*canSleep=*/false);
  const btQuaternion no_rotation = btQuaternion::getIdentity();
  const btVector3 zero(0, 0, 0);
  auto base_shape = std::make_unique<btCompoundShape>();
  btTransform at_base_com;
  at_base_com.setIdentity();
  base_shape->addChildShape(at_base_com, torso_shape_);
  for (int leg = 0; leg < 4; ++leg) {
    const LegGeometry& g = kLegs[leg];
    const CapsuleLink& stub = legs_[leg].stub;
    const CapsuleLink& thigh = legs_[leg].thigh;
    const CapsuleLink& foot = legs_[leg].foot;
    const btVector3 stub_end(g.sign_x * kStubLength, g.sign_y * kStubLength, 0);
    const int hip = 2 * leg;
    const int ankle = hip + 1;
    // The stub's capsule, at the place its faithful link puts it (its
    // compound shifts it by −com_offset from the stub COM, i.e. to the torso centre).
    base_shape->addChildShape(at_base_com, stub.spheres);
    // Pivots as the faithful chain reaches them: base COM → stub COM → hip.
    const btVector3 hip_pivot_from_base_com = stub.com_offset + (stub_end - stub.com_offset);
    body->setupRevolute(hip, thigh.mass, thigh.inertia, -1, no_rotation, btVector3(0, 0, 1),
                        hip_pivot_from_base_com, thigh.com_offset,
                        /*disableParentCollision=*/true);
    body->setupRevolute(ankle, foot.mass, foot.inertia, hip, no_rotation,
                        btVector3(g.ankle_axis_x, 1, 0), stub_end - thigh.com_offset,
                        foot.com_offset, /*disableParentCollision=*/true);
    const int first = 5 * leg;
    link_places_[first] = {-1, stub.com_offset};             // <leg>: in the base
    link_places_[first + 1] = {hip, -thigh.com_offset};      // hip_k: the hip pivot
    link_places_[first + 2] = {hip, zero};                   // thigh COM
    link_places_[first + 3] = {ankle, -foot.com_offset};     // ankle_k: the ankle pivot
    link_places_[first + 4] = {ankle, zero};                 // foot COM
    movable_links_[2 * leg] = hip;
    movable_links_[2 * leg + 1] = ankle;
  }
  body->finalizeMultiDof();
  body->setHasSelfCollision(false);
  body_ = world_.add_multibody(std::move(body));

  add_collider(-1, world_.keep_shape(std::move(base_shape)));
  for (int leg = 0; leg < 4; ++leg) {
    add_collider(2 * leg, legs_[leg].thigh.shape);
    feet_[leg] = add_collider(2 * leg + 1, legs_[leg].foot.shape);
  }
  add_joint_limits();
}

void AntAgent::refresh_colliders() {
  body_->forwardKinematics(scratch_rotations_, scratch_vectors_);
  body_->updateCollisionObjectWorldTransforms(scratch_rotations_, scratch_vectors_);
}

void AntAgent::reset(Rng& rng) {
  // Velocities to zero and the base back to its initial pose (the snapshot
  // restore of docs/environments.md#reset, step 1 reduces to this, docs/environments.md#how-bodies-are-built).
  body_->setBaseVel(btVector3(0, 0, 0));
  body_->setBaseOmega(btVector3(0, 0, 0));
  body_->setBasePos(traits_.initial_position);
  body_->setWorldToBaseRot(btQuaternion::getIdentity());
  // 8 draws in joint order: hips U(−0.1, 0.1); ankles ±(π/2 + U(−0.1, 0.1))
  // with the sign of their limit range (docs/environments.md#ant).
  std::array<double, kActionDim> q{};
  for (int k = 0; k < kActionDim; ++k) {
    const double noise = uniform(rng, -0.1, 0.1);
    const bool ankle = k % 2 == 1;
    q[k] = !ankle ? noise : (kLimits[k].lower > 0 ? 1.0 : -1.0) * (std::numbers::pi / 2 + noise);
  }
  set_joint_positions(q);
  // The reset observation shows no feet contacts (docs/environments.md#reset, step 5).
  feet_contact_.fill(0);
  last_action_.fill(0);
  joints_at_limit_reward_ = 0;
  electricity_reward_ = 0;
  specific_reward_ = 0;
}

void AntAgent::set_base_pose(const btVector3& com_position, const btQuaternion& orientation) {
  body_->setBasePos(com_position);
  // btMultiBody stores the world-to-base rotation (docs/environments.md#how-bodies-are-built).
  body_->setWorldToBaseRot(orientation.inverse());
  refresh_colliders();
}

void AntAgent::set_joint_positions(std::span<const double> joint_positions) {
  if (joint_positions.size() != static_cast<size_t>(kActionDim)) {
    throw std::invalid_argument("AntAgent::set_joint_positions: expected 8 joint angles, got " +
                                std::to_string(joint_positions.size()));
  }
  for (int k = 0; k < kActionDim; ++k) {
    body_->setJointPos(movable_links_[k], joint_positions[k]);
    body_->setJointVel(movable_links_[k], 0);
  }
  refresh_colliders();
}

void AntAgent::apply_action(std::span<const double> action) {
  if (action.size() != static_cast<size_t>(kActionDim)) {
    throw std::invalid_argument("AntAgent::apply_action: expected 8 actions, got " +
                                std::to_string(action.size()));
  }
  for (int k = 0; k < kActionDim; ++k) {
    last_action_[k] = action[k];
    // τ_k = (power·100)·clip(a_k, −1, 1), held for all sub-steps (docs/environments.md#ant, #motors-forces-and-contacts).
    const double clipped = std::clamp(action[k], -1.0, 1.0);
    body_->addJointTorque(movable_links_[k], torque_per_unit_action_ * clipped);
  }
}

void AntAgent::after_step() {
  // Feet touching the ground body (not walls or obstacles), docs/environments.md#ant.
  for (int f = 0; f < kFootCount; ++f) {
    feet_contact_[f] = world_.touching(feet_[f], world_.ground()) ? 1.0 : 0.0;
  }
  // J and E from the float32-rounded joint values (docs/environments.md#ant);
  // E uses the raw, unclipped action (docs/environments.md#kept-quirks, item 5).
  int at_limit = 0;
  std::array<double, kActionDim> power{};
  std::array<double, kActionDim> action_squared{};
  for (int k = 0; k < kActionDim; ++k) {
    const int link = movable_links_[k];
    const float rho = relative_position(body_->getJointPos(link), kLimits[k]);
    if (std::abs(rho) > kAtLimitThreshold) ++at_limit;
    const double a = last_action_[k];
    power[k] = std::abs(a * static_cast<double>(scaled_rate(body_->getJointVel(link))));
    action_squared[k] = a * a;
  }
  joints_at_limit_reward_ = kJointsAtLimitCost * at_limit;
  electricity_reward_ = kElectricityCost * numpy_mean8(power);
  electricity_reward_ += kStallTorqueCost * numpy_mean8(action_squared);
  // s_ant = alive + E + J + feet term (always 0), summed in the original's order.
  const double alive_bonus = alive() ? 1.0 : -1.0;
  specific_reward_ = ((alive_bonus + electricity_reward_) + joints_at_limit_reward_) + 0.0;
}

void AntAgent::write_observation(std::span<double> out) const {
  if (out.size() != static_cast<size_t>(kObservationDim)) {
    throw std::invalid_argument("AntAgent::write_observation: expected 33 entries, got " +
                                std::to_string(out.size()));
  }
  // [0.1·p, 0.3·v, quaternion, 0.15·ω, (ρ_k/2, 0.05·q̇_k) for k = 0..7, feet] (docs/environments.md#ant).
  const btVector3 p = position();
  const btVector3 v = linear_velocity();
  const btQuaternion q = orientation();
  const btVector3 w = angular_velocity();
  int i = 0;
  for (int axis = 0; axis < 3; ++axis) out[i++] = 0.1 * p[axis];
  for (int axis = 0; axis < 3; ++axis) out[i++] = 0.3 * v[axis];
  out[i++] = q.x();
  out[i++] = q.y();
  out[i++] = q.z();
  out[i++] = q.w();
  for (int axis = 0; axis < 3; ++axis) out[i++] = 0.15 * w[axis];
  for (int k = 0; k < kActionDim; ++k) {
    const int link = movable_links_[k];
    // 0.5·float32 is exact, so halving in double gives the same number.
    out[i++] = 0.5 * static_cast<double>(relative_position(body_->getJointPos(link), kLimits[k]));
    out[i++] = 0.5 * static_cast<double>(scaled_rate(body_->getJointVel(link)));
  }
  for (int f = 0; f < kFootCount; ++f) out[i++] = feet_contact_[f];
}

bool AntAgent::alive() const { return body_->getBasePos().z() > kAliveHeight; }

btVector3 AntAgent::position() const { return body_->getBasePos(); }

btQuaternion AntAgent::orientation() const { return body_->getWorldToBaseRot().inverse(); }

btVector3 AntAgent::linear_velocity() const { return body_->getBaseVel(); }

btVector3 AntAgent::angular_velocity() const { return body_->getBaseOmega(); }

void AntAgent::joint_state(std::span<double> positions, std::span<double> velocities) const {
  if (positions.size() != static_cast<size_t>(kActionDim) ||
      velocities.size() != static_cast<size_t>(kActionDim)) {
    throw std::invalid_argument("AntAgent::joint_state: expected 8 positions and velocities, got " +
                                std::to_string(positions.size()) + " and " +
                                std::to_string(velocities.size()));
  }
  for (int k = 0; k < kActionDim; ++k) {
    positions[k] = body_->getJointPos(movable_links_[k]);
    velocities[k] = body_->getJointVel(movable_links_[k]);
  }
}

double AntAgent::total_mass_kg() const {
  double mass = body_->getBaseMass();
  for (int link = 0; link < body_->getNumLinks(); ++link) mass += body_->getLinkMass(link);
  return mass;
}

btTransform AntAgent::link_com_transform(int link) const {
  if (link < 0 || link >= kLinkCount) {
    throw std::out_of_range("AntAgent::link_com_transform: link " + std::to_string(link) +
                            " outside [0, 20)");
  }
  const LinkPlace& place = link_places_[link];
  btTransform pose;
  pose.setOrigin(body_->localPosToWorld(place.body_link, place.offset));
  pose.setBasis(body_->localFrameToWorld(place.body_link, btMatrix3x3::getIdentity()));
  return pose;
}

std::unique_ptr<Agent> make_ant_agent(World& world, const AgentOptions& options) {
  return std::make_unique<AntAgent>(world, options);
}

}  // namespace bsg::envs
