#include "envs/agents/ball_agent.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <BulletCollision/CollisionShapes/btSphereShape.h>
#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <BulletDynamics/Featherstone/btMultiBodyLinkCollider.h>

#include "envs/physics/multibody_pose.h"
#include "envs/physics/world.h"

namespace bsg::envs {
namespace {

// ball.urdf's <contact> block (docs/environments.md#ball).
constexpr double kLateralFriction = 1.1;
constexpr double kRollingFriction = 0.03;
constexpr double kSpinningFriction = 0.03;
constexpr double kRestitution = 0.7;

AgentTraits ball_traits() {
  AgentTraits traits;
  traits.action_dim = 2;
  traits.observation_dim = 7;
  traits.initial_position = btVector3(0, 0, 0.5);
  traits.initial_yaw = 0;
  traits.collision_radius = 0.5;
  traits.run_speed_limit = 2.5;
  traits.sensor_rotates = false;
  traits.sensor_offset = btVector3(0, 0, 0);
  return traits;
}

}  // namespace

BallAgent::BallAgent(World& world, const AgentOptions& /*options: no power upgrade*/)
    : traits_(ball_traits()) {
  // Inertia from the collision sphere, 2/5·m·r² = 0.03 (the URDF's 1 is
  // ignored by PyBullet, docs/environments.md#how-bodies-are-built).
  const double inertia = 0.4 * kMass * kRadius * kRadius;
  auto body = std::make_unique<btMultiBody>(0, kMass, btVector3(inertia, inertia, inertia),
                                            /*fixedBase=*/false, /*canSleep=*/false);
  body->setBasePos(traits_.initial_position);
  body->setWorldToBaseRot(btQuaternion::getIdentity());
  body->setHasSelfCollision(false);
  body->finalizeMultiDof();
  body_ = world.add_multibody(std::move(body));

  auto* sphere = world.keep_shape(std::make_unique<btSphereShape>(kRadius));
  auto collider = std::make_unique<btMultiBodyLinkCollider>(body_, -1);
  collider->setCollisionShape(sphere);
  collider->setFriction(kLateralFriction);
  collider->setRollingFriction(kRollingFriction);
  collider->setSpinningFriction(kSpinningFriction);
  collider->setRestitution(kRestitution);
  btTransform pose;
  pose.setIdentity();
  pose.setOrigin(traits_.initial_position);
  collider->setWorldTransform(pose);
  btMultiBodyLinkCollider* added = world.add_collider(std::move(collider));
  body_->setBaseCollider(added);
  colliders_[0] = added;
}

void BallAgent::reset(Rng& /*rng: the Ball draws nothing*/) {
  body_->setBaseVel(btVector3(0, 0, 0));
  body_->setBaseOmega(btVector3(0, 0, 0));
  teleport_base(*body_, traits_.initial_position, btQuaternion::getIdentity());
  specific_reward_ = 0;
}

void BallAgent::set_base_pose(const btVector3& com_position, const btQuaternion& orientation) {
  teleport_base(*body_, com_position, orientation);
}

void BallAgent::set_joint_positions(std::span<const double> joint_positions) {
  if (!joint_positions.empty()) {
    throw std::invalid_argument("Ball has no joints, got " +
                                std::to_string(joint_positions.size()) + " joint positions");
  }
}

void BallAgent::apply_action(std::span<const double> action) {
  const double a0 = std::clamp(action[0], -1.0, 1.0);
  const double a1 = std::clamp(action[1], -1.0, 1.0);
  // World-frame force at the COM: no torque (docs/environments.md#ball); Bullet holds it for
  // every sub-step and clears it after the engine step (docs/environments.md#motors-forces-and-contacts).
  body_->addBaseForce(btVector3(kForcePerAction * a0, kForcePerAction * a1, 0));
  specific_reward_ = -0.5 * std::sqrt(a0 * a0 + a1 * a1);  // s_ball = −0.5·‖a‖₂
}

void BallAgent::write_observation(std::span<double> out) const {
  const btVector3 p = body_->getBasePos();
  const btVector3 v = body_->getBaseVel();
  const btVector3 w = body_->getBaseOmega();
  out[0] = 0.1 * p.x();
  out[1] = 0.1 * p.y();
  out[2] = 0.2 * v.x();
  out[3] = 0.2 * v.y();
  out[4] = 0.1 * w.x();
  out[5] = 0.1 * w.y();
  out[6] = 0.1 * w.z();
}

btVector3 BallAgent::position() const { return body_->getBasePos(); }
btQuaternion BallAgent::orientation() const { return base_orientation(*body_); }
btVector3 BallAgent::linear_velocity() const { return body_->getBaseVel(); }
btVector3 BallAgent::angular_velocity() const { return body_->getBaseOmega(); }

void BallAgent::joint_state(std::span<double> /*positions*/,
                            std::span<double> /*velocities*/) const {}

std::unique_ptr<Agent> make_ball_agent(World& world, const AgentOptions& options) {
  return std::make_unique<BallAgent>(world, options);
}

}  // namespace bsg::envs
