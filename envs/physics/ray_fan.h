// Many rays cast from one origin (a LIDAR's sensor mount) against a World,
// with the results of World::ray_hit_fraction for each ray, but without one
// broadphase traversal and, for boxes, without GJK per ray.
//
// World::ray_hit_fraction runs Bullet's rayTest: a walk of both broadphase
// trees per ray, then the GJK ray cast (rayTestSingle) on every collider whose
// broadphase box the ray crosses, keeping the smallest hit fraction. The fan
// instead collects, once, the few colliders whose broadphase boxes lie within
// reach of the origin, and per ray applies Bullet's own ray-box test to each
// of them. A collider that is a box, or a compound of boxes (each behind the
// same ray-box test against its box in the compound's tree, as Bullet does),
// is then cast by cast_ray_at_box: Bullet's conservative advancement with the
// point-box distance in closed form, equal to Bullet's up to rounding (the
// fraction within 1e-9 in tests/envs/physics/lidar_fan_test.cpp; hit or miss alike
// except for a ray that passes within 1 mm of a box without entering it and
// ends its advancement where it runs parallel to the surface, a decision that
// rests on the last bits of Bullet's own normal). Any other collider, and any
// box ray cast_ray_at_box leaves undecided, goes to rayTestSingle. The closest
// hit is the minimum over colliders (and compound children) of results that
// do not depend on the order in which they are tried.
//
// Parameters:
//   reach_m         longest ray to be cast (the LIDAR range, 5 in Reach)
//   kMaxCandidates  colliders kept near the origin (16); beyond that every ray
//                   falls back to World::ray_hit_fraction
//   kMaxBoxes       boxes cast in closed form (32); a collider whose boxes do
//                   not fit takes rayTestSingle
#pragma once

#include <array>
#include <span>

#include <LinearMath/btVector3.h>

#include "envs/physics/ray_box_cast.h"

class btCollisionObject;
class btCollisionShape;
struct btDbvtNode;

namespace bsg::envs {

class World;

class RayFan {
 public:
  static constexpr int kMaxCandidates = 16;
  static constexpr int kMaxBoxes = 32;

  // Rays start at `origin` and are at most `reach_m` long; colliders in
  // `ignore` (the agent's own) are never hit. Both `world` and `ignore` must
  // outlive the fan; the world must not step while the fan is used.
  RayFan(const World& world, const btVector3& origin, double reach_m,
         std::span<const btCollisionObject* const> ignore);

  // World::ray_hit_fraction(origin, to, ignore): closest-hit fraction in
  // [0, 1], 1 if nothing is hit. A ray longer than reach_m takes the generic path.
  double hit_fraction(const btVector3& to) const;

  // Colliders kept for the rays (for tests); -1 after a fallback.
  int candidate_count() const { return overflow_ ? -1 : count_; }
  // Boxes among them cast in closed form (for tests).
  int closed_form_box_count() const { return box_count_; }

 private:
  struct Candidate {
    const btCollisionObject* object;
    const btDbvtNode* leaf;  // its broadphase box, as Bullet's rayTest sees it
    int first_box;           // its boxes: boxes_[first_box, first_box + box_count)
    int box_count;           // 0: rayTestSingle on the whole collider
    bool compound;           // the boxes are children of its compound shape
  };
  // One child of a compound, or the collider's own box shape.
  struct BoxTarget {
    const btCollisionShape* shape;  // for rayTestSingle when not in closed form
    RoundedBox box;                 // its world placement (valid if closed_form)
    bool closed_form;               // a btBoxShape cast_ray_at_box handles
    const btDbvtNode* child_leaf;   // its box in the compound's tree; nullptr: none
  };

  // Appends the collider's boxes to boxes_; false if it has none to cast in
  // closed form or they do not fit.
  bool collect_boxes(const btCollisionObject& object, Candidate& candidate);

  const World& world_;
  btVector3 origin_;
  double longest_ray2_;  // squared length beyond which a ray takes the generic path
  std::span<const btCollisionObject* const> ignore_;
  std::array<Candidate, kMaxCandidates> candidates_;
  std::array<BoxTarget, kMaxBoxes> boxes_;
  int count_ = 0;
  int box_count_ = 0;
  bool overflow_ = false;
};

}  // namespace bsg::envs
