#include "envs/physics/world.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include <BulletCollision/BroadphaseCollision/btDbvtBroadphase.h>
#include <BulletCollision/CollisionDispatch/btCollisionDispatcher.h>
#include <BulletCollision/CollisionDispatch/btDefaultCollisionConfiguration.h>
#include <BulletCollision/CollisionShapes/btBoxShape.h>
#include <BulletCollision/CollisionShapes/btCompoundShape.h>
#include <BulletCollision/NarrowPhaseCollision/btPersistentManifold.h>
#include <BulletCollision/NarrowPhaseCollision/btRaycastCallback.h>
#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <BulletDynamics/Featherstone/btMultiBodyConstraint.h>
#include <BulletDynamics/Featherstone/btMultiBodyConstraintSolver.h>
#include <BulletDynamics/Featherstone/btMultiBodyDynamicsWorld.h>
#include <BulletDynamics/Featherstone/btMultiBodyLinkCollider.h>

#include "envs/physics/bullet_block_pool.h"
#include "envs/physics/deterministic_pair_cache.h"

namespace bsg::envs {
namespace {

// URDF importer's collision margin for boxes (Bullet's own default is 0.04).
constexpr double kBoxMargin = 0.001;
constexpr double kGroundFriction = 0.8;
constexpr double kGroundRestitution = 0.5;
constexpr double kWallFriction = 0.5;
constexpr double kWallRestitution = 0.0;

// Closest hit that skips the agent's own colliders (PyBullet's rayTestBatch,
// where the agent is never hit in practice, docs/environments.md#motors-forces-and-contacts).
class ClosestHitIgnoring : public btCollisionWorld::ClosestRayResultCallback {
 public:
  ClosestHitIgnoring(const btVector3& from, const btVector3& to,
                     std::span<const btCollisionObject* const> ignore)
      : ClosestRayResultCallback(from, to), ignore_(ignore) {
    m_flags |= btTriangleRaycastCallback::kF_UseGjkConvexCastRaytest;
    // The ray belongs to every group: with Bullet's default ray group (1 =
    // kStaticGroup) the static scenery, whose mask excludes its own group,
    // would never be hit. PyBullet's rays use collision mask "all" (docs/environments.md#motors-forces-and-contacts).
    m_collisionFilterGroup = kAllGroups;
    m_collisionFilterMask = kAllGroups;
  }
  bool needsCollision(btBroadphaseProxy* proxy) const override {
    const auto* object = static_cast<const btCollisionObject*>(proxy->m_clientObject);
    if (std::find(ignore_.begin(), ignore_.end(), object) != ignore_.end()) return false;
    return ClosestRayResultCallback::needsCollision(proxy);
  }

 private:
  std::span<const btCollisionObject* const> ignore_;
};

}  // namespace

World::World(WorldLayout layout, int sub_steps)
    : World(layout, sub_steps, kEnvStepSeconds / std::max(sub_steps, 1)) {
  env_step_seconds_ = kEnvStepSeconds;  // exactly, whatever the sub-steps
}

World::World(WorldLayout layout, int sub_steps, double time_step_seconds)
    : layout_(layout),
      sub_steps_(sub_steps),
      time_step_(time_step_seconds),
      env_step_seconds_(time_step_seconds * sub_steps) {
  if (sub_steps < 1) {
    throw std::invalid_argument("World: sub_steps must be >= 1, got " + std::to_string(sub_steps));
  }
  if (!(time_step_seconds > 0)) {
    throw std::invalid_argument("World: time_step must be > 0 s, got " + std::to_string(time_step_seconds));
  }
  install_bullet_block_pool();
  // PyBullet sets the broadphase's AABB margin to 0 (docs/environments.md#physics-settings). Bullet keeps it
  // in a library-wide variable; every World sets the same value.
  gDbvtMargin = 0;
  collision_configuration_ = std::make_unique<btDefaultCollisionConfiguration>();
  dispatcher_ = std::make_unique<btCollisionDispatcher>(collision_configuration_.get());
  pair_cache_ = std::make_unique<DeterministicPairCache>();
  broadphase_ = std::make_unique<btDbvtBroadphase>(pair_cache_.get());
  solver_ = std::make_unique<btMultiBodyConstraintSolver>();
  dynamics_ = std::make_unique<btMultiBodyDynamicsWorld>(
      dispatcher_.get(), broadphase_.get(), solver_.get(), collision_configuration_.get());
  dynamics_->setGravity(btVector3(0, 0, kGravity));
  dynamics_->getDispatchInfo().m_deterministicOverlappingPairs = true;
  // Bullet recomputes every object's bounding box at every internal step by
  // default; the ground and walls never move, so only moving bodies need it
  // (about 8 % of a Ball step; contacts are unchanged).
  dynamics_->setForceUpdateAllAabbs(false);

  btContactSolverInfo& info = dynamics_->getSolverInfo();
  info.m_numIterations = 5;
  info.m_erp2 = 0.9;  // setDefaultContactERP(0.9)
  // PyBullet's non-default solver settings (docs/environments.md#physics-settings).
  info.m_frictionERP = 0.2;
  info.m_linearSlop = 1e-5;
  info.m_minimumSolverBatchSize = 0;
  info.m_warmstartingFactor = 0.1;
  info.m_leastSquaresResidualThreshold = 1e-7;

  build_layout();
}

World::~World() {
  // Remove in reverse order of dependency before the world itself goes.
  for (auto& constraint : constraints_) dynamics_->removeMultiBodyConstraint(constraint.get());
  for (auto& collider : colliders_) dynamics_->removeCollisionObject(collider.get());
  for (auto& body : bodies_) dynamics_->removeMultiBody(body.get());
  for (auto& object : static_objects_) dynamics_->removeCollisionObject(object.get());
}

double World::env_dim() const { return layout_ == WorldLayout::kPlane200 ? 250.0 : 10.0; }

void World::step() {
  // (1/60)/(1/60/n) is exact for n in {1, 4}, so Bullet performs exactly n
  // internal steps per call (docs/environments.md#physics-settings).
  dynamics_->stepSimulation(env_step_seconds(), sub_steps_, internal_step_seconds());
}

btCollisionShape* World::keep_shape(std::unique_ptr<btCollisionShape> shape) {
  shapes_.push_back(std::move(shape));
  return shapes_.back().get();
}

btMultiBody* World::add_multibody(std::unique_ptr<btMultiBody> body) {
  dynamics_->addMultiBody(body.get());
  bodies_.push_back(std::move(body));
  return bodies_.back().get();
}

btMultiBodyLinkCollider* World::add_collider(std::unique_ptr<btMultiBodyLinkCollider> collider,
                                             int group, int mask) {
  dynamics_->addCollisionObject(collider.get(), group, mask);
  colliders_.push_back(std::move(collider));
  return colliders_.back().get();
}

btMultiBodyConstraint* World::add_constraint(std::unique_ptr<btMultiBodyConstraint> constraint) {
  dynamics_->addMultiBodyConstraint(constraint.get());
  constraints_.push_back(std::move(constraint));
  return constraints_.back().get();
}

const btCollisionObject* World::add_static_box(const btVector3& half_extents,
                                               const btVector3& centre, double yaw,
                                               double friction, double restitution) {
  auto box = std::make_unique<btBoxShape>(half_extents);
  box->setMargin(kBoxMargin);
  btCollisionShape* shape = keep_shape(std::move(box));
  btTransform transform;
  transform.setIdentity();
  transform.setOrigin(centre);
  transform.setRotation(btQuaternion(btVector3(0, 0, 1), yaw));
  return add_static_object(shape, transform, friction, restitution);
}

const btCollisionObject* World::add_static_offset_box(const btVector3& half_extents,
                                                      const btVector3& link_origin,
                                                      const btVector3& box_offset,
                                                      double friction, double restitution) {
  auto box = std::make_unique<btBoxShape>(half_extents);
  box->setMargin(kBoxMargin);
  btCollisionShape* box_shape = keep_shape(std::move(box));
  auto compound = std::make_unique<btCompoundShape>();
  btTransform child;
  child.setIdentity();
  child.setOrigin(box_offset);
  compound->addChildShape(child, box_shape);
  btCollisionShape* shape = keep_shape(std::move(compound));
  btTransform transform;
  transform.setIdentity();
  transform.setOrigin(link_origin);
  return add_static_object(shape, transform, friction, restitution);
}

const btCollisionObject* World::add_static_object(btCollisionShape* shape,
                                                  const btTransform& transform, double friction,
                                                  double restitution) {
  auto object = std::make_unique<btCollisionObject>();
  object->setCollisionShape(shape);
  object->setWorldTransform(transform);
  object->setFriction(friction);
  object->setRestitution(restitution);
  object->setCollisionFlags(object->getCollisionFlags() | btCollisionObject::CF_STATIC_OBJECT);
  dynamics_->addCollisionObject(object.get(), kStaticGroup, kAllGroups ^ kStaticGroup);
  // Asleep, as Bullet puts every static rigid body: the world then skips its
  // bounding box, which never changes, at every internal step (with
  // setForceUpdateAllAabbs(false) only active objects are updated). A contact
  // needs one active body of the two, and the agents never sleep.
  object->setActivationState(ISLAND_SLEEPING);
  static_objects_.push_back(std::move(object));
  return static_objects_.back().get();
}

const btCollisionObject* World::add_ground(const btVector3& half_extents) {
  // The ground URDFs put the link frame on the top face (z = 0) and the
  // collision box half a height below it. Contacts are computed in the
  // object's frame, so this placement, not just the box's world extent,
  // decides the last bits of every contact with the ground (measured against
  // the golden trajectories: a box centred at -h/2 misses them by ~1e-6).
  return add_static_offset_box(half_extents, {0, 0, 0}, {0, 0, -half_extents.z()},
                               kGroundFriction, kGroundRestitution);
}

void World::build_layout() {
  // The ground is created first, as PyBullet's body 0 (docs/environments.md#worlds).
  switch (layout_) {
    case WorldLayout::kSmallRoom: {
      ground_ = add_ground({10, 10, 5});
      add_static_box({10.1, 0.1, 1}, {0, 10, 1}, 0, kWallFriction, kWallRestitution);
      add_static_box({10.1, 0.1, 1}, {0, -10, 1}, 0, kWallFriction, kWallRestitution);
      add_static_box({0.1, 10, 1}, {10, 0, 1}, 0, kWallFriction, kWallRestitution);
      add_static_box({0.1, 10, 1}, {-10, 0, 1}, 0, kWallFriction, kWallRestitution);
      break;
    }
    case WorldLayout::kOctagon: {
      ground_ = add_ground({15, 15, 5});
      for (int k = 0; k < 8; ++k) {
        const double theta = k * std::numbers::pi / 4;  // θk = kπ/4, thin side radial
        add_static_box({0.1, 5, 1}, {12 * std::cos(theta), 12 * std::sin(theta), 1}, theta,
                       kWallFriction, kWallRestitution);
      }
      break;
    }
    case WorldLayout::kPlane200: {
      ground_ = add_ground({250, 250, 1});
      break;
    }
  }
}

double World::ray_hit_fraction(const btVector3& from, const btVector3& to,
                               std::span<const btCollisionObject* const> ignore) const {
  ClosestHitIgnoring callback(from, to, ignore);
  dynamics_->rayTest(from, to, callback);
  return callback.hasHit() ? callback.m_closestHitFraction : 1.0;
}

bool World::touching(const btCollisionObject* a, const btCollisionObject* b) const {
  const int manifolds = dispatcher_->getNumManifolds();
  for (int i = 0; i < manifolds; ++i) {
    const btPersistentManifold* manifold = dispatcher_->getManifoldByIndexInternal(i);
    if (manifold->getNumContacts() == 0) continue;
    const btCollisionObject* first = manifold->getBody0();
    const btCollisionObject* second = manifold->getBody1();
    if ((first == a && second == b) || (first == b && second == a)) return true;
  }
  return false;
}

int World::contact_points(const btCollisionObject* a,
                          std::span<const btCollisionObject* const> others) const {
  int points = 0;
  const int manifolds = dispatcher_->getNumManifolds();
  for (int i = 0; i < manifolds; ++i) {
    const btPersistentManifold* manifold = dispatcher_->getManifoldByIndexInternal(i);
    const btCollisionObject* first = manifold->getBody0();
    const btCollisionObject* second = manifold->getBody1();
    const btCollisionObject* other = first == a ? second : (second == a ? first : nullptr);
    if (other != nullptr && std::find(others.begin(), others.end(), other) != others.end()) {
      points += manifold->getNumContacts();
    }
  }
  return points;
}

void World::forget_contacts() {
  const int manifolds = dispatcher_->getNumManifolds();
  for (int i = 0; i < manifolds; ++i) {
    dispatcher_->clearManifold(dispatcher_->getManifoldByIndexInternal(i));
  }
}

}  // namespace bsg::envs
