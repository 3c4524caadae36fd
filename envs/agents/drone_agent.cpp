#include "envs/agents/drone_agent.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include <BulletCollision/CollisionShapes/btBoxShape.h>
#include <BulletCollision/CollisionShapes/btCompoundShape.h>
#include <BulletCollision/CollisionShapes/btConvexHullShape.h>
#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <BulletDynamics/Featherstone/btMultiBodyJointMotor.h>
#include <BulletDynamics/Featherstone/btMultiBodyLinkCollider.h>
#include <LinearMath/btMatrix3x3.h>
#include <LinearMath/btTransform.h>

#include "envs/physics/orientation.h"
#include "envs/physics/world.h"

namespace bsg::envs {
namespace {

constexpr double kPi = std::numbers::pi;

// Thrust-model constants of the original's Drone class (docs/environments.md#drone); they do not
// follow the ×2 scaling of the model.
constexpr double kRotorRadius = 0.14;                 // r [m]
constexpr double kPropellerPitch = 4.7 * 0.0254;      // p [m]
constexpr double kK1 = 1.0 / 3.29546;                 // k₁
constexpr double kK2 = 1.5;                           // k₂
constexpr double kAirDensity = 1.225;                 // ρ [kg/m³]
constexpr double kNominalMass = 1.420;                // m [kg] (thrust model only)
constexpr double kGravity = 9.81;                     // g [m/s²]
constexpr double kActionRange = 0.1;                  // ±10 % of ω_h per unit action
constexpr double kMotorForce = 23.444;                // velocity-motor force F
constexpr double kMaxJointVelocity = 1000;            // changeDynamics(maxJointVelocity)
constexpr std::array<double, 4> kRotorDirections = {+1, -1, +1, -1};  // d_i

// Multibody model (docs/environments.md#drone; lengths already ×2).
constexpr int kLinkCount = 5;       // body box + 4 rotors; the base is a dummy
constexpr int kBodyLink = 0;        // base_link_inertia, fixed to the base
constexpr int kFirstRotorLink = 1;  // rotor_i is link 1 + i
constexpr double kBaseMass = 1e-6;
constexpr double kBodyMass = 1.4;
constexpr double kRotorMass = 0.005;
constexpr double kBodyHalfExtents[3] = {0.3, 0.3, 0.17};  // box 0.6 × 0.6 × 0.34
constexpr double kRotorHullRadius = 0.28;
constexpr double kRotorHullHalfLength = 0.005;     // cylinder length 0.01
constexpr int kRotorHullSegments = 32;             // URDF cylinder → 32-gon prism (docs/environments.md#how-bodies-are-built)
constexpr double kCollisionMargin = 0.001;         // URDF importer default (docs/environments.md#how-bodies-are-built)
constexpr double kFriction = 0.5;                  // no <contact> tags
// Rotor joint origins in the base frame.
constexpr double kRotorOffsets[4][3] = {
    {0.34, 0, 0.02}, {0, -0.34, 0.02}, {-0.34, 0, 0.02}, {0, 0.34, 0.02}};

// s_drone (docs/environments.md#drone).
constexpr double kAliveReward = 1.0;
constexpr double kDeathReward = -10.0;
constexpr double kSpinPenalty = 0.01;
constexpr double kRotorObservationScale = 2.5e-3;

// The disc area A = π·r², written as the original computes it.
double rotor_area_m2() { return kPi * (kRotorRadius * kRotorRadius); }

// btConvexHullShape of the URDF importer's cylinder (docs/environments.md#how-bodies-are-built): 32 points on
// each end cap, angle 2π·k/32, margin 0.001.
std::unique_ptr<btConvexHullShape> make_rotor_hull() {
  auto hull = std::make_unique<btConvexHullShape>();
  for (int k = 0; k < kRotorHullSegments; ++k) {
    const double angle = 2 * kPi * (static_cast<float>(k) / kRotorHullSegments);
    const btVector3 top(kRotorHullRadius * std::sin(angle), kRotorHullRadius * std::cos(angle),
                        kRotorHullHalfLength);
    hull->addPoint(top, false);
    hull->addPoint(btVector3(top.x(), top.y(), -kRotorHullHalfLength), false);
  }
  hull->setMargin(kCollisionMargin);
  hull->recalcLocalAabb();
  // The importer then re-computes the hull, which quantises the vertices
  // slightly; the AABB (and so the inertia) keeps the exact points.
  hull->optimizeConvexHull();
  return hull;
}

class DroneAgent final : public Agent {
 public:
  DroneAgent(World& world, const AgentOptions& options);

  const AgentTraits& traits() const override { return traits_; }
  void reset(Rng& rng) override;
  void set_base_pose(const btVector3& com_position, const btQuaternion& orientation) override;
  void set_joint_positions(std::span<const double> joint_positions) override;
  int movable_joint_count() const override { return kRotorCount; }
  void apply_action(std::span<const double> action) override;
  void after_step() override;
  void write_observation(std::span<double> out) const override;
  double specific_reward() const override;
  bool alive() const override;
  btVector3 position() const override { return body_->getBasePos(); }
  btQuaternion orientation() const override;
  btVector3 linear_velocity() const override { return body_->getBaseVel(); }
  btVector3 angular_velocity() const override { return body_->getBaseOmega(); }
  void joint_state(std::span<double> positions, std::span<double> velocities) const override;
  std::span<const btCollisionObject* const> colliders() const override { return colliders_; }

 private:
  static constexpr int kRotorCount = 4;

  // Link frames and colliders follow a teleport at once, as after PyBullet's
  // resetBasePositionAndOrientation / resetJointState (forward kinematics also
  // refreshes the cached link transforms that the thrust uses).
  void refresh_kinematics();

  World& world_;
  AgentTraits traits_;
  btMultiBody* body_ = nullptr;
  std::array<btMultiBodyJointMotor*, kRotorCount> motors_{};
  std::array<const btCollisionObject*, kLinkCount + 1> colliders_{};  // base, links 0..4
  double hover_speed_rad_per_s_ = 0;  // ω_h
  double env_step_seconds_ = 0;       // T_param, bounds the motor impulses
  int ground_contacts_ = 0;           // n_g after the last step (stale until then, docs/environments.md#kept-quirks, item 10)
  btAlignedObjectArray<btQuaternion> scratch_world_to_local_;
  btAlignedObjectArray<btVector3> scratch_local_origin_;
};

DroneAgent::DroneAgent(World& world, const AgentOptions& /*options: no power upgrade, docs/environments.md#agents*/)
    : world_(world),
      hover_speed_rad_per_s_(drone_hover_speed_rad_per_s()),
      env_step_seconds_(world.env_step_seconds()) {
  traits_.action_dim = 4;
  traits_.observation_dim = 17;
  traits_.initial_position = btVector3(0, 0, 0.17);  // the body box touches the ground
  traits_.initial_yaw = 0;
  traits_.collision_radius = 0.5;
  traits_.run_speed_limit = 1.5;
  traits_.sensor_rotates = true;
  traits_.sensor_offset = btVector3(0, 0, 0);

  // Inertias come from the collision shapes (docs/environments.md#how-bodies-are-built): Bullet's box formula
  // for the body, the hull's AABB approximation for the rotors; the dummy base
  // has no shape and hence zero inertia.
  auto body_box = std::make_unique<btBoxShape>(
      btVector3(kBodyHalfExtents[0], kBodyHalfExtents[1], kBodyHalfExtents[2]));
  body_box->setMargin(kCollisionMargin);
  btCollisionShape* body_shape = world.keep_shape(std::move(body_box));
  btCollisionShape* rotor_shape = world.keep_shape(make_rotor_hull());
  btVector3 body_inertia(0, 0, 0);
  body_shape->calculateLocalInertia(kBodyMass, body_inertia);
  btVector3 rotor_inertia(0, 0, 0);
  rotor_shape->calculateLocalInertia(kRotorMass, rotor_inertia);

  auto multibody = std::make_unique<btMultiBody>(kLinkCount, kBaseMass, btVector3(0, 0, 0),
                                                 /*fixedBase=*/false, /*canSleep=*/false);
  const btQuaternion identity = btQuaternion::getIdentity();
  const btVector3 zero(0, 0, 0);
  multibody->setupFixed(kBodyLink, kBodyMass, body_inertia, -1, identity, zero, zero);
  for (int i = 0; i < kRotorCount; ++i) {
    // Continuous joints: revolute without limit about the rotor's z axis.
    multibody->setupRevolute(kFirstRotorLink + i, kRotorMass, rotor_inertia, -1, identity,
                             btVector3(0, 0, 1),
                             btVector3(kRotorOffsets[i][0], kRotorOffsets[i][1], kRotorOffsets[i][2]),
                             zero,
                             /*disableParentCollision=*/true);
  }
  multibody->finalizeMultiDof();
  multibody->setHasSelfCollision(false);  // loaded without URDF_USE_SELF_COLLISION (docs/environments.md#how-bodies-are-built)
  // PyBullet's default 100 rad/s clamp would sit below hover speed (docs/environments.md#drone).
  multibody->setMaxCoordinateVelocity(kMaxJointVelocity);
  multibody->setBasePos(traits_.initial_position);
  multibody->setWorldToBaseRot(btQuaternion::getIdentity());
  body_ = multibody.get();

  // The URDF importer gives every link a collider, the shapeless dummy base an
  // empty compound (it never touches anything but takes part in the broadphase
  // and the simulation islands as in PyBullet). Colliders enter the world at
  // their link poses, base first, then links 0..4, and before the multibody.
  btCollisionShape* base_shape = world.keep_shape(std::make_unique<btCompoundShape>());
  std::array<std::unique_ptr<btMultiBodyLinkCollider>, kLinkCount + 1> new_colliders;
  for (int link = -1; link < kLinkCount; ++link) {
    auto collider = std::make_unique<btMultiBodyLinkCollider>(body_, link);
    collider->setCollisionShape(link == -1 ? base_shape
                                : link == kBodyLink ? body_shape
                                                    : rotor_shape);
    collider->setFriction(kFriction);
    collider->setRestitution(0);
    collider->setRollingFriction(0);
    collider->setSpinningFriction(0);
    if (link == -1) {
      body_->setBaseCollider(collider.get());
    } else {
      body_->getLink(link).m_collider = collider.get();
    }
    new_colliders[link + 1] = std::move(collider);
  }
  refresh_kinematics();
  for (int index = 0; index <= kLinkCount; ++index) {
    colliders_[index] = world.add_collider(std::move(new_colliders[index]));
  }
  world.add_multibody(std::move(multibody));

  // PyBullet creates a velocity motor per rotor joint at load; the original
  // switches it off at construction (force 0 → max impulse 0 removes its row,
  // docs/environments.md#motors-forces-and-contacts), so the rotors start free.
  for (int i = 0; i < kRotorCount; ++i) {
    auto motor = std::make_unique<btMultiBodyJointMotor>(body_, kFirstRotorLink + i, 0,
                                                         /*desiredVelocity=*/0.0,
                                                         /*maxMotorImpulse=*/0.0);
    motor->setPositionTarget(0, 0);
    motor->setVelocityTarget(0, 1);
    motor->finalizeMultiDof();
    motors_[i] = static_cast<btMultiBodyJointMotor*>(world.add_constraint(std::move(motor)));
  }
}

void DroneAgent::refresh_kinematics() {
  body_->forwardKinematics(scratch_world_to_local_, scratch_local_origin_);
  body_->updateCollisionObjectWorldTransforms(scratch_world_to_local_, scratch_local_origin_);
}

void DroneAgent::reset(Rng& rng) {
  // Snapshot restore (docs/environments.md#reset, step 1): initial pose, all velocities zero; then the
  // agent reset (docs/environments.md#drone): rotor angles U(−0.1, 0.1), rotor rates 0. Motor targets
  // are left alone: they survive the reset (docs/environments.md#kept-quirks, item 10), and so does n_g.
  body_->setBasePos(traits_.initial_position);
  body_->setWorldToBaseRot(btQuaternion::getIdentity());
  body_->setBaseVel(btVector3(0, 0, 0));
  body_->setBaseOmega(btVector3(0, 0, 0));
  for (int i = 0; i < kRotorCount; ++i) {
    body_->setJointPos(kFirstRotorLink + i, uniform(rng, -0.1, 0.1));
    body_->setJointVel(kFirstRotorLink + i, 0);
  }
  refresh_kinematics();
}

void DroneAgent::set_base_pose(const btVector3& com_position, const btQuaternion& orientation) {
  body_->setBasePos(com_position);
  body_->setWorldToBaseRot(orientation.inverse());
  refresh_kinematics();
}

void DroneAgent::set_joint_positions(std::span<const double> joint_positions) {
  if (joint_positions.size() != kRotorCount) {
    throw std::invalid_argument("Drone: set_joint_positions needs 4 rotor angles, got " +
                                std::to_string(joint_positions.size()));
  }
  for (int i = 0; i < kRotorCount; ++i) {
    body_->setJointPos(kFirstRotorLink + i, joint_positions[i]);
    body_->setJointVel(kFirstRotorLink + i, 0);
  }
  refresh_kinematics();
}

btQuaternion DroneAgent::orientation() const {
  // PyBullet reports the base rotation after a quaternion → matrix → quaternion
  // round trip (getBaseWorldTransform().getRotation()); the thrust axis, the
  // observation and the alive test all start from that value.
  return body_->getBaseWorldTransform().getRotation();
}

void DroneAgent::apply_action(std::span<const double> action) {
  if (action.size() != kRotorCount) {
    throw std::invalid_argument("Drone: action needs 4 entries, got " +
                                std::to_string(action.size()));
  }
  // v₀ = v_base · (R·e_z): the COM velocity along the body's up axis, R from the
  // base quaternion at the time of the call (docs/environments.md#drone).
  const btVector3 up = btMatrix3x3(orientation()).getColumn(2);
  const btVector3 velocity = body_->getBaseVel();
  const double inflow_m_per_s = velocity.x() * up.x() + velocity.y() * up.y() + velocity.z() * up.z();

  for (int i = 0; i < kRotorCount; ++i) {
    const double a = std::clamp(action[i], -1.0, 1.0);
    // ω*_i = d_i·ω_h·(1 + 0.1·a_i)
    const double target_rad_per_s =
        (kRotorDirections[i] * hover_speed_rad_per_s_) * (1 + kActionRange * a);
    // Velocity motor, kd 1, kp 0, max impulse F·T_param per internal step (docs/environments.md#motors-forces-and-contacts).
    btMultiBodyJointMotor* motor = motors_[i];
    motor->setVelocityTarget(target_rad_per_s, 1.0);
    motor->setPositionTarget(0, 0);
    motor->setRhsClamp(SIMD_INFINITY);
    motor->setMaxAppliedImpulse(kMotorForce * env_step_seconds_);

    // Thrust from the commanded speed (docs/environments.md#kept-quirks, item 7) along the rotor's z axis, as a
    // LINK_FRAME force at the rotor origin. PyBullet rotates it with the link's
    // cached transform, left by the start of the last internal step
    // (docs/environments.md#drone); the force at the COM carries no torque.
    const double thrust_n =
        drone_thrust_newton(target_rad_per_s * kRotorDirections[i], inflow_m_per_s);
    const int link = kFirstRotorLink + i;
    const btMatrix3x3& rotor_basis = body_->getLink(link).m_cachedWorldTransform.getBasis();
    body_->addLinkForce(link, rotor_basis * btVector3(0, 0, thrust_n));
  }
}

void DroneAgent::after_step() {
  // n_g: links (body box, rotors) with at least one contact point with the
  // ground after the last internal step (docs/environments.md#drone); the base's empty shape
  // never has one.
  int count = 0;
  for (const btCollisionObject* collider : colliders_) {
    if (world_.touching(collider, world_.ground())) ++count;
  }
  ground_contacts_ = count;
}

void DroneAgent::write_observation(std::span<double> out) const {
  if (out.size() != static_cast<size_t>(traits_.observation_dim)) {
    throw std::invalid_argument("Drone: observation buffer needs 17 entries, got " +
                                std::to_string(out.size()));
  }
  const btVector3 p = body_->getBasePos();
  const btVector3 v = body_->getBaseVel();
  const btVector3 w = body_->getBaseOmega();
  // The original canonicalises the quaternion through Euler angles (docs/environments.md#drone).
  const RollPitchYaw rpy = euler_from_quaternion(orientation());
  const btQuaternion q = quaternion_from_euler(rpy.roll, rpy.pitch, rpy.yaw);
  const std::array<double, 13> base = {0.1 * p.x(), 0.1 * p.y(), 0.1 * p.z(), 0.2 * v.x(),
                                       0.2 * v.y(), 0.2 * v.z(), q.x(),       q.y(),
                                       q.z(),       q.w(),       0.1 * w.x(), 0.1 * w.y(),
                                       0.1 * w.z()};
  std::copy(base.begin(), base.end(), out.begin());
  for (int i = 0; i < kRotorCount; ++i) {
    // 2.5e-3·(ω_i − d_i·ω_h), with the unrounded ω_h (docs/environments.md#drone).
    const double hover_rad_per_s = kRotorDirections[i] * hover_speed_rad_per_s_;
    out[13 + i] =
        kRotorObservationScale * (body_->getJointVel(kFirstRotorLink + i) - hover_rad_per_s);
  }
}

double DroneAgent::specific_reward() const {
  // s_drone = (1 if alive else −10) − 0.01·‖ω_base‖² − n_g, with ‖ω‖² formed as
  // the original does (norm, then squared).
  const btVector3 w = body_->getBaseOmega();
  const double norm = std::sqrt(w.x() * w.x() + w.y() * w.y() + w.z() * w.z());
  const double alive_term = alive() ? kAliveReward : kDeathReward;
  return alive_term - kSpinPenalty * (norm * norm) - ground_contacts_;
}

bool DroneAgent::alive() const {
  // |roll| ≤ π/2 and |pitch| ≤ π/2 from PyBullet's Euler angles; pitch = asin(·)
  // never exceeds π/2, so only roll can end an episode (docs/environments.md#kept-quirks, item 6).
  const RollPitchYaw rpy = euler_from_quaternion(orientation());
  constexpr double kLimit = 0.5 * kPi;
  return std::abs(rpy.pitch) <= kLimit && std::abs(rpy.roll) <= kLimit;
}

void DroneAgent::joint_state(std::span<double> positions, std::span<double> velocities) const {
  if (positions.size() != kRotorCount || velocities.size() != kRotorCount) {
    throw std::invalid_argument("Drone: joint_state needs spans of 4 entries, got " +
                                std::to_string(positions.size()) + " and " +
                                std::to_string(velocities.size()));
  }
  for (int i = 0; i < kRotorCount; ++i) {
    positions[i] = body_->getJointPos(kFirstRotorLink + i);
    velocities[i] = body_->getJointVel(kFirstRotorLink + i);
  }
}

}  // namespace

double drone_hover_speed_rad_per_s() {
  // (2π/p)·((m·g/4)/(ρ·A)·(p/(k₁·D))^k₂)^0.5 with D = 2r, in the original's order.
  const double rotor_weight_n = kNominalMass * kGravity / 4.0;
  const double p = kPropellerPitch;
  const double diameter_m = 2.0 * kRotorRadius;
  return (2 * kPi / p) *
         std::pow(rotor_weight_n / (kAirDensity * rotor_area_m2()) *
                      std::pow(p / (kK1 * diameter_m), kK2),
                  0.5);
}

double drone_thrust_newton(double rotor_speed_rad_per_s, double inflow_speed_m_per_s) {
  // n = ω/(2π)·p; the original recovers D from the area: D = (4A/π)^0.5.
  const double area_m2 = rotor_area_m2();
  const double n = rotor_speed_rad_per_s / (2 * kPi) * kPropellerPitch;
  const double diameter_m = std::pow(4.0 * area_m2 / kPi, 0.5);
  return kAirDensity * area_m2 * (n * n - n * inflow_speed_m_per_s) *
         std::pow(kK1 * diameter_m / kPropellerPitch, kK2);
}

std::unique_ptr<Agent> make_drone_agent(World& world, const AgentOptions& options) {
  return std::make_unique<DroneAgent>(world, options);
}

}  // namespace bsg::envs
