#include "ray_fan.h"

#include <algorithm>

#include <BulletCollision/BroadphaseCollision/btDbvtBroadphase.h>
#include <BulletCollision/CollisionDispatch/btCollisionWorld.h>
#include <BulletCollision/NarrowPhaseCollision/btRaycastCallback.h>
#include <BulletDynamics/Featherstone/btMultiBodyDynamicsWorld.h>
#include <LinearMath/btAabbUtil2.h>

#include "world.h"

namespace bsg::envs {
namespace {

// Slack added to the reach when collecting colliders. A broadphase box that
// misses the cube of half side reach + slack around the origin is missed by
// every ray of length <= reach + slack/2: Bullet's ray-box test then finds its
// entry parameter beyond the ray's end, or its exit before the start, by at
// least slack/2, far more than rounding (~1e-15 m) could undo. Half the slack
// also lets a LIDAR ray of length 5·|R·d| = 5 ± 1e-15 pass as "within reach".
constexpr double kReachSlack_m = 1e-3;

// The closest-hit bookkeeping of World::ray_hit_fraction's callback
// (ClosestRayResultCallback with the GJK ray test and mask "all"), minus the
// hit point and normal nobody reads. rayTestSingle reports only hits closer
// than m_closestHitFraction, so the last report is the closest.
class ClosestFraction final : public btCollisionWorld::RayResultCallback {
 public:
  ClosestFraction() {
    m_flags |= btTriangleRaycastCallback::kF_UseGjkConvexCastRaytest;
    m_collisionFilterGroup = kAllGroups;
    m_collisionFilterMask = kAllGroups;
  }
  btScalar addSingleResult(btCollisionWorld::LocalRayResult& result, bool) override {
    m_closestHitFraction = result.m_hitFraction;
    m_collisionObject = result.m_collisionObject;
    return result.m_hitFraction;
  }
};

bool overlaps(const btDbvtAabbMm& box, const btVector3& low, const btVector3& high) {
  return box.Mins().x() <= high.x() && box.Maxs().x() >= low.x() &&
         box.Mins().y() <= high.y() && box.Maxs().y() >= low.y() &&
         box.Mins().z() <= high.z() && box.Maxs().z() >= low.z();
}

}  // namespace

RayFan::RayFan(const World& world, const btVector3& origin, double reach_m,
               std::span<const btCollisionObject* const> ignore)
    : world_(world),
      origin_(origin),
      longest_ray2_((reach_m + kReachSlack_m / 2) * (reach_m + kReachSlack_m / 2)),
      ignore_(ignore) {
  const btCollisionWorld& dynamics = world.dynamics();
  // The broadphase boxes below are the leaves of btDbvtBroadphase, the one
  // World builds; any other broadphase takes the generic path.
  if (dynamic_cast<const btDbvtBroadphase*>(dynamics.getBroadphase()) == nullptr) {
    overflow_ = true;
    return;
  }
  const double half_side = reach_m + kReachSlack_m;
  const btVector3 low = origin - btVector3(half_side, half_side, half_side);
  const btVector3 high = origin + btVector3(half_side, half_side, half_side);
  const ClosestFraction filter;
  const btCollisionObjectArray& objects = dynamics.getCollisionObjectArray();
  for (int i = 0; i < objects.size(); ++i) {
    const btCollisionObject* object = objects[i];
    // World::ray_hit_fraction's filter: not the agent's, and a collision
    // group and mask that a ray of group and mask "all" accepts (Bullet's
    // filter takes a mutable proxy but only reads it).
    if (std::find(ignore.begin(), ignore.end(), object) != ignore.end()) continue;
    auto* proxy = const_cast<btBroadphaseProxy*>(object->getBroadphaseHandle());
    if (!filter.needsCollision(proxy)) continue;
    const btDbvtNode* leaf = static_cast<const btDbvtProxy*>(proxy)->leaf;
    if (!overlaps(leaf->volume, low, high)) continue;
    if (count_ == kMaxCandidates) {
      overflow_ = true;
      return;
    }
    candidates_[static_cast<size_t>(count_++)] = {object, leaf};
  }
}

double RayFan::hit_fraction(const btVector3& to) const {
  const btVector3 ray = to - origin_;
  // The candidates were chosen for rays up to reach_m (+ slack/2) long.
  if (overflow_ || ray.length2() > longest_ray2_) {
    return world_.ray_hit_fraction(origin_, to, ignore_);
  }
  if (count_ == 0) return 1.0;
  // The ray parameters exactly as btCollisionWorld::rayTest computes them
  // (btSingleRayCallback) for btDbvtBroadphase's ray-box test.
  btVector3 direction = ray;
  direction.normalize();
  btVector3 inverse_direction;
  unsigned int signs[3];
  for (int k = 0; k < 3; ++k) {
    inverse_direction[k] = direction[k] == btScalar(0) ? btScalar(BT_LARGE_FLOAT)
                                                       : btScalar(1) / direction[k];
    signs[k] = inverse_direction[k] < 0.0;
  }
  const btScalar lambda_max = direction.dot(ray);

  btTransform from_transform;
  from_transform.setIdentity();
  from_transform.setOrigin(origin_);
  btTransform to_transform;
  to_transform.setIdentity();
  to_transform.setOrigin(to);
  ClosestFraction closest;
  for (int i = 0; i < count_; ++i) {
    // Bullet stops once a hit at the very start is found; nothing is closer.
    if (closest.m_closestHitFraction == btScalar(0)) break;
    const Candidate& candidate = candidates_[static_cast<size_t>(i)];
    // btDbvt::rayTestInternal's bounds are the leaf box minus the ray's own
    // box, (0,0,0) for a ray: subtracting zero changes no bit. Its test of the
    // parent nodes is implied: they contain the leaf, and the test is monotone.
    const btVector3 bounds[2] = {candidate.leaf->volume.Mins(), candidate.leaf->volume.Maxs()};
    btScalar entry = 1;
    if (!btRayAabb2(origin_, inverse_direction, signs, bounds, entry, 0, lambda_max)) continue;
    btCollisionObject* object = const_cast<btCollisionObject*>(candidate.object);  // Bullet's API
    btCollisionWorld::rayTestSingle(from_transform, to_transform, object,
                                    object->getCollisionShape(), object->getWorldTransform(),
                                    closest);
  }
  return closest.hasHit() ? closest.m_closestHitFraction : 1.0;
}

}  // namespace bsg::envs
