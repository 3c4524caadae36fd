// The physics world of one environment: Bullet's multibody dynamics world with
// the original suite's settings (docs/environments.md#physics-settings), its ground and walls (docs/environments.md#worlds), the
// engine step with its sub-steps, ray casts and contact queries. It owns every
// Bullet object created in it, so agents, tasks and obstacles only borrow.
//
// Parameters:
//   layout     SmallRoom (Reach, Gather), Octagon (Circle) or Plane200 (Run)
//   sub_steps  internal steps per environment step: 4 (Circle, Run, Gather), 1 (Reach)
//   time_step  one internal step [s]: 1/(60·sub_steps) unless given (EnvDescription)
#pragma once

#include <memory>
#include <span>
#include <vector>

#include <LinearMath/btTransform.h>
#include <LinearMath/btVector3.h>

class btBroadphaseInterface;
class btOverlappingPairCache;
class btCollisionDispatcher;
class btCollisionObject;
class btCollisionShape;
class btDefaultCollisionConfiguration;
class btMultiBody;
class btMultiBodyConstraint;
class btMultiBodyConstraintSolver;
class btMultiBodyDynamicsWorld;
class btMultiBodyLinkCollider;

namespace bsg::envs {

enum class WorldLayout { kSmallRoom, kOctagon, kPlane200 };

// Collision filter groups. Agents and the dynamic Box collide with everything;
// static scenery does not collide with itself.
inline constexpr int kStaticGroup = 1;
inline constexpr int kDynamicGroup = 2;
inline constexpr int kAllGroups = -1;

class World {
 public:
  // Duration of one environment step (1/60 s) and PyBullet's fixed-time-step
  // parameter T_param, which also bounds motor impulses (docs/environments.md#motors-forces-and-contacts).
  static constexpr double kEnvStepSeconds = 1.0 / 60.0;
  static constexpr double kGravity = -9.81;

  World(WorldLayout layout, int sub_steps);
  // Internal steps of `time_step_seconds` (the fork's other step lengths).
  World(WorldLayout layout, int sub_steps, double time_step_seconds);
  ~World();
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  WorldLayout layout() const { return layout_; }
  int sub_steps() const { return sub_steps_; }
  double internal_step_seconds() const { return time_step_; }
  // T_param: the duration of one environment step, time_step · sub_steps
  // (1/60 s in every standard environment).
  double env_step_seconds() const { return env_step_seconds_; }
  // Scale used by sensors and observations: 10 for SmallRoom and Octagon
  // (Octagon's ground is 30 m wide: original quirk, docs/environments.md#kept-quirks, item 15), 250 for Plane200.
  double env_dim() const;

  // One environment step: `sub_steps` internal steps of 1/(60·sub_steps) s.
  // Forces and joint torques added before the call act during every sub-step
  // and are cleared at the end (docs/environments.md#motors-forces-and-contacts).
  void step();

  btMultiBodyDynamicsWorld& dynamics() { return *dynamics_; }
  const btMultiBodyDynamicsWorld& dynamics() const { return *dynamics_; }

  // The ground's collider (PyBullet body 0, base link).
  const btCollisionObject* ground() const { return ground_; }

  // Takes ownership of a collision shape, returns it for use.
  btCollisionShape* keep_shape(std::unique_ptr<btCollisionShape> shape);
  // Adds a multibody to the world and takes ownership of it. Add its link
  // colliders with add_collider() afterwards.
  btMultiBody* add_multibody(std::unique_ptr<btMultiBody> body);
  // Adds a multibody link collider (link -1 is the base) with the given filter.
  btMultiBodyLinkCollider* add_collider(std::unique_ptr<btMultiBodyLinkCollider> collider,
                                        int group = kDynamicGroup, int mask = kAllGroups);
  btMultiBodyConstraint* add_constraint(std::unique_ptr<btMultiBodyConstraint> constraint);
  // A static box (mass 0) centred at `centre`, rotated by `yaw` about z,
  // with half extents `half_extents` and the given friction/restitution.
  const btCollisionObject* add_static_box(const btVector3& half_extents, const btVector3& centre,
                                          double yaw, double friction, double restitution);
  // A static box whose collision object sits at `link_origin` and whose box is
  // offset by `box_offset` inside a compound shape: how PyBullet's URDF
  // importer builds a link with an offset <collision> origin.
  const btCollisionObject* add_static_offset_box(const btVector3& half_extents,
                                                 const btVector3& link_origin,
                                                 const btVector3& box_offset, double friction,
                                                 double restitution);

  // Fraction f in [0, 1] of the segment from→to at which the closest collider
  // not in `ignore` is hit; 1 if nothing is hit (PyBullet's rayTest, docs/environments.md#lidar).
  double ray_hit_fraction(const btVector3& from, const btVector3& to,
                          std::span<const btCollisionObject* const> ignore) const;

  // True if a persistent contact manifold between a and b holds at least one
  // point after the last internal step (PyBullet's getContactPoints, docs/environments.md#motors-forces-and-contacts).
  bool touching(const btCollisionObject* a, const btCollisionObject* b) const;
  // Number of contact points between `a` and any collider in `others`.
  int contact_points(const btCollisionObject* a,
                     std::span<const btCollisionObject* const> others) const;

  // Empties every cached contact manifold, so that the next step starts
  // without warm-starting from earlier contacts. PyBullet's restoreState at
  // reset brings back the manifolds of the snapshot, which is taken before any
  // collision detection ran, i.e. none (docs/environments.md#motors-forces-and-contacts, #reset, step 1).
  void forget_contacts();

 private:
  void build_layout();
  const btCollisionObject* add_ground(const btVector3& half_extents);
  const btCollisionObject* add_static_object(btCollisionShape* shape, const btTransform& transform,
                                             double friction, double restitution);

  WorldLayout layout_;
  int sub_steps_;
  double time_step_;
  double env_step_seconds_;
  std::unique_ptr<btDefaultCollisionConfiguration> collision_configuration_;
  std::unique_ptr<btCollisionDispatcher> dispatcher_;
  std::unique_ptr<btOverlappingPairCache> pair_cache_;  // outlives the broadphase using it
  std::unique_ptr<btBroadphaseInterface> broadphase_;
  std::unique_ptr<btMultiBodyConstraintSolver> solver_;
  std::unique_ptr<btMultiBodyDynamicsWorld> dynamics_;
  std::vector<std::unique_ptr<btCollisionShape>> shapes_;
  std::vector<std::unique_ptr<btCollisionObject>> static_objects_;
  std::vector<std::unique_ptr<btMultiBody>> bodies_;
  std::vector<std::unique_ptr<btMultiBodyLinkCollider>> colliders_;
  std::vector<std::unique_ptr<btMultiBodyConstraint>> constraints_;
  const btCollisionObject* ground_ = nullptr;
};

}  // namespace bsg::envs
