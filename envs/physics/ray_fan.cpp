#include "envs/physics/ray_fan.h"

#include <algorithm>

#include <BulletCollision/BroadphaseCollision/btDbvtBroadphase.h>
#include <BulletCollision/CollisionDispatch/btCollisionWorld.h>
#include <BulletCollision/CollisionShapes/btBoxShape.h>
#include <BulletCollision/CollisionShapes/btCompoundShape.h>
#include <BulletCollision/NarrowPhaseCollision/btRaycastCallback.h>
#include <BulletDynamics/Featherstone/btMultiBodyDynamicsWorld.h>
#include <LinearMath/btAabbUtil2.h>

#include "envs/physics/world.h"

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
  // A closed-form hit, kept as rayTestSingleInternal keeps one: only if closer.
  void offer(const btCollisionObject* object, double fraction) {
    if (fraction < m_closestHitFraction) {
      m_closestHitFraction = fraction;
      m_collisionObject = object;
    }
  }
};

bool overlaps(const btDbvtAabbMm& box, const btVector3& low, const btVector3& high) {
  return box.Mins().x() <= high.x() && box.Maxs().x() >= low.x() &&
         box.Mins().y() <= high.y() && box.Maxs().y() >= low.y() &&
         box.Mins().z() <= high.z() && box.Maxs().z() >= low.z();
}

// The parameters of Bullet's ray-box test (btRayAabb2) for the ray from→to,
// computed as both btCollisionWorld::rayTest (btSingleRayCallback) and
// btDbvt::rayTest compute them.
struct RayBoxTest {
  btVector3 from;
  btVector3 inverse_direction;
  unsigned int signs[3];
  btScalar lambda_max;

  RayBoxTest(const btVector3& ray_from, const btVector3& ray_to) : from(ray_from) {
    btVector3 direction = ray_to - ray_from;
    direction.normalize();
    for (int k = 0; k < 3; ++k) {
      inverse_direction[k] = direction[k] == btScalar(0) ? btScalar(BT_LARGE_FLOAT)
                                                         : btScalar(1) / direction[k];
      signs[k] = inverse_direction[k] < 0.0;
    }
    lambda_max = direction.dot(ray_to - ray_from);
  }

  // btDbvt's test of a node (rayTestInternal's bounds are the box minus the
  // ray's own box, (0,0,0) for a ray: subtracting zero changes no bit). The
  // test of a node's ancestors is implied: they contain it, and it is monotone.
  bool crosses(const btDbvtNode& node) const {
    const btVector3 bounds[2] = {node.volume.Mins(), node.volume.Maxs()};
    btScalar entry = 1;
    return btRayAabb2(from, inverse_direction, signs, bounds, entry, 0, lambda_max);
  }
};

bool is_box(const btCollisionShape& shape) {
  return shape.getShapeType() == BOX_SHAPE_PROXYTYPE;
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
    Candidate& candidate = candidates_[static_cast<size_t>(count_++)];
    candidate = {object, leaf, box_count_, 0, false};
    if (!collect_boxes(*object, candidate)) {
      box_count_ = candidate.first_box;  // drop a partial compound
      candidate.box_count = 0;
    }
  }
}

bool RayFan::collect_boxes(const btCollisionObject& object, Candidate& candidate) {
  const btCollisionShape& shape = *object.getCollisionShape();
  const btTransform& pose = object.getWorldTransform();
  // What a ray test of one child shape sees, as rayTestSingleInternal sets it up.
  const auto add = [&](const btCollisionShape& child, const btTransform& placement,
                       const btDbvtNode* child_leaf) {
    if (box_count_ == kMaxBoxes) return false;
    BoxTarget& target = boxes_[static_cast<size_t>(box_count_++)];
    target.shape = &child;
    target.closed_form = is_box(child);
    if (target.closed_form) {
      target.box = rounded_box(static_cast<const btBoxShape&>(child), placement);
    } else {
      target.box.transform = placement;
    }
    target.child_leaf = child_leaf;
    ++candidate.box_count;
    return true;
  };

  if (is_box(shape)) return add(shape, pose, nullptr);
  if (!shape.isCompound()) return false;
  // Bullet offers no const access to a compound's children list; it is only read.
  auto& compound = const_cast<btCompoundShape&>(static_cast<const btCompoundShape&>(shape));
  // rayTestSingleInternal tests each child behind its box in the compound's
  // tree when there is one, every child otherwise.
  const bool has_tree = compound.getDynamicAabbTree() != nullptr;
  candidate.compound = true;
  bool any_box = false;
  for (int c = 0; c < compound.getNumChildShapes(); ++c) {
    const btCollisionShape& child = *compound.getChildShape(c);
    const btDbvtNode* child_leaf = has_tree ? compound.getChildList()[c].m_node : nullptr;
    if (has_tree && child_leaf == nullptr) return false;
    // The child's world transform exactly as Bullet forms it.
    const btTransform placement = pose * compound.getChildTransform(c);
    if (!add(child, placement, child_leaf)) return false;
    any_box = any_box || is_box(child);
  }
  return any_box;
}

double RayFan::hit_fraction(const btVector3& to) const {
  const btVector3 ray = to - origin_;
  // The candidates were chosen for rays up to reach_m (+ slack/2) long.
  if (overflow_ || ray.length2() > longest_ray2_) {
    return world_.ray_hit_fraction(origin_, to, ignore_);
  }
  if (count_ == 0) return 1.0;
  // The ray parameters exactly as btCollisionWorld::rayTest computes them for
  // btDbvtBroadphase's ray-box test.
  const RayBoxTest world_ray(origin_, to);

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
    if (!world_ray.crosses(*candidate.leaf)) continue;
    btCollisionObject* object = const_cast<btCollisionObject*>(candidate.object);  // Bullet's API
    if (candidate.box_count == 0) {
      btCollisionWorld::rayTestSingle(from_transform, to_transform, object,
                                      object->getCollisionShape(), object->getWorldTransform(),
                                      closest);
      continue;
    }
    // btDbvt::rayTest's parameters for the ray in the compound's frame
    // (colObjWorldTransform.inverseTimes(ray transform).getOrigin()).
    const btTransform& pose = object->getWorldTransform();
    const RayBoxTest compound_ray =
        candidate.compound ? RayBoxTest((origin_ - pose.getOrigin()) * pose.getBasis(),
                                        (to - pose.getOrigin()) * pose.getBasis())
                           : world_ray;
    for (int b = candidate.first_box; b < candidate.first_box + candidate.box_count; ++b) {
      const BoxTarget& target = boxes_[static_cast<size_t>(b)];
      if (target.child_leaf != nullptr && !compound_ray.crosses(*target.child_leaf)) continue;
      if (target.closed_form) {
        const RayBoxHit hit = cast_ray_at_box(origin_, to, target.box);
        if (hit.outcome == RayBoxOutcome::kHit) closest.offer(object, hit.fraction);
        if (hit.outcome != RayBoxOutcome::kUndecided) continue;
      }
      // What rayTestSingleInternal does for this child (or the box itself).
      btCollisionWorld::rayTestSingle(from_transform, to_transform, object, target.shape,
                                      target.box.transform, closest);
    }
  }
  return closest.hasHit() ? closest.m_closestHitFraction : 1.0;
}

}  // namespace bsg::envs
