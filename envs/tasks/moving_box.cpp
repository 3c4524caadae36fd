#include "envs/tasks/moving_box.h"

#include <cmath>
#include <memory>

#include <BulletCollision/CollisionShapes/btBoxShape.h>
#include <BulletCollision/CollisionShapes/btCompoundShape.h>
#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <BulletDynamics/Featherstone/btMultiBodyFixedConstraint.h>
#include <BulletDynamics/Featherstone/btMultiBodyLinkCollider.h>

#include "envs/physics/multibody_pose.h"
#include "envs/physics/world.h"

namespace bsg::envs {
namespace {

constexpr double kHalfWidth = 0.5;
constexpr double kHalfHeight = 0.75;
constexpr double kMargin = 0.001;  // URDF importer's box margin (docs/environments.md#how-bodies-are-built)

// PyBullet's inertia of the URDF link: Bullet's compound-shape approximation,
// the inertia of the shape's bounding box, whose extents include the margin
// (docs/environments.md#how-bodies-are-built): (1.35834, 1.35834, 0.83667).
btVector3 box_inertia() {
  const double lx = 2 * (kHalfWidth + kMargin);
  const double lz = 2 * (kHalfHeight + kMargin);
  constexpr double kMass = MovingBox::kMass;
  const double side = kMass / 12 * (lx * lx + lz * lz);
  return {side, side, kMass / 12 * (lx * lx + lx * lx)};
}

}  // namespace

MovingBox::MovingBox(World& world, double circle_radius) : circle_radius_(circle_radius) {
  auto body = std::make_unique<btMultiBody>(0, kMass, box_inertia(), /*fixedBase=*/false,
                                            /*canSleep=*/false);
  body->setBasePos(btVector3(0, 0, 0));
  body->setWorldToBaseRot(btQuaternion::getIdentity());
  body->setHasSelfCollision(false);
  body->finalizeMultiDof();
  body_ = world.add_multibody(std::move(body));

  // The box's centre lies 0.75 m above its origin (the COM, bottom face).
  auto box = std::make_unique<btBoxShape>(btVector3(kHalfWidth, kHalfWidth, kHalfHeight));
  box->setMargin(kMargin);
  auto compound = std::make_unique<btCompoundShape>();
  btTransform offset;
  offset.setIdentity();
  offset.setOrigin(btVector3(0, 0, kHalfHeight));
  compound->addChildShape(offset, world.keep_shape(std::move(box)));
  btCollisionShape* shape = world.keep_shape(std::move(compound));

  auto collider = std::make_unique<btMultiBodyLinkCollider>(body_, -1);
  collider->setCollisionShape(shape);
  collider->setFriction(kFriction);
  collider->setRestitution(kRestitution);
  btTransform pose;
  pose.setIdentity();
  collider->setWorldTransform(pose);
  btMultiBodyLinkCollider* added = world.add_collider(std::move(collider));
  body_->setBaseCollider(added);
  collider_ = added;

  // Fixed constraint between the box base (pivot 0, frame I) and the world
  // (pivot P, frame I): PyBullet's createConstraint(JOINT_FIXED, child = −1).
  const btMatrix3x3 identity = btMatrix3x3::getIdentity();
  auto constraint = std::make_unique<btMultiBodyFixedConstraint>(
      body_, -1, static_cast<btRigidBody*>(nullptr), btVector3(0, 0, 0), btVector3(0, 0, 0),
      identity, identity);
  constraint->setMaxAppliedImpulse(kMaxImpulse);
  constraint_ = static_cast<btMultiBodyFixedConstraint*>(world.add_constraint(std::move(constraint)));
}

void MovingBox::place(const btVector3& centre, const btQuaternion& orientation, double phase,
                      double clock_seconds) {
  body_->setBaseVel(btVector3(0, 0, 0));
  body_->setBaseOmega(btVector3(0, 0, 0));
  teleport_base(*body_, centre, orientation);
  centre_ = centre;
  phase_ = phase;
  move(clock_seconds);
}

void MovingBox::move(double clock_seconds) {
  clock_seconds_ = clock_seconds;
  const double angle = clock_seconds + phase_;
  pivot_ = btVector3(centre_.x() + circle_radius_ * std::sin(angle),
                     centre_.y() + circle_radius_ * std::cos(angle), centre_.z());
  constraint_->setPivotInB(pivot_);
}

btVector3 MovingBox::position() const { return body_->getBasePos(); }
btQuaternion MovingBox::orientation() const { return base_orientation(*body_); }
btVector3 MovingBox::linear_velocity() const { return body_->getBaseVel(); }
btVector3 MovingBox::angular_velocity() const { return body_->getBaseOmega(); }

}  // namespace bsg::envs
