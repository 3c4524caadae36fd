// The Box of Reach (docs/environments.md#obstacles, #moving-box): a dynamic 1×1×1.5 m box of 5 kg whose
// bottom-face centre is held by a fixed constraint (max impulse 500 per
// internal step) to a world pivot that circles its centre c:
//   P(t) = c + 0.7·(sin(t + φ), cos(t + φ), 0).
// Both constraint frames are identity, so the constraint also turns the box to
// yaw 0. The clock t is supplied by the environment (docs/environments.md#moving-box).
#pragma once

#include <LinearMath/btQuaternion.h>
#include <LinearMath/btVector3.h>

class btCollisionObject;
class btMultiBody;
class btMultiBodyFixedConstraint;

namespace bsg::envs {

class World;

class MovingBox {
 public:
  static constexpr double kMass = 5.0;
  static constexpr double kCircleRadius = 0.7;    // [m]
  static constexpr double kMaxImpulse = 500.0;    // PyBullet's default per internal step
  static constexpr double kFriction = 0.9;
  static constexpr double kRestitution = 0.4;

  explicit MovingBox(World& world, double circle_radius = kCircleRadius);

  // Teleports the box to circle centre `centre` with `orientation` and zero
  // velocity, and sets its pivot to P(clock_seconds) (docs/environments.md#moving-box: "whenever
  // the box is placed at c its circle centre becomes c").
  void place(const btVector3& centre, const btQuaternion& orientation, double phase,
             double clock_seconds);
  // Moves the pivot to P(clock_seconds); called before every engine step.
  void move(double clock_seconds);

  btVector3 position() const;  // bottom-face centre = COM
  btQuaternion orientation() const;
  btVector3 linear_velocity() const;
  btVector3 angular_velocity() const;
  const btVector3& pivot() const { return pivot_; }
  double clock_seconds() const { return clock_seconds_; }
  double phase() const { return phase_; }
  const btCollisionObject* collider() const { return collider_; }

 private:
  double circle_radius_;
  btMultiBody* body_ = nullptr;
  btMultiBodyFixedConstraint* constraint_ = nullptr;
  const btCollisionObject* collider_ = nullptr;
  btVector3 centre_{0, 0, 0};
  btVector3 pivot_{0, 0, 0};
  double phase_ = 0;
  double clock_seconds_ = 0;
};

}  // namespace bsg::envs
