// Many rays cast from one origin (a LIDAR's sensor mount) against a World,
// with exactly the results of World::ray_hit_fraction for each ray, bit for bit,
// but without one broadphase traversal per ray.
//
// World::ray_hit_fraction runs Bullet's rayTest: a walk of both broadphase
// trees per ray, then the GJK ray cast (rayTestSingle) on every collider whose
// broadphase box the ray crosses, keeping the smallest hit fraction. The fan
// instead collects, once, the few colliders whose broadphase boxes lie within
// reach of the origin, and per ray applies Bullet's own ray-box test to each
// of them before the same rayTestSingle. The closest hit is the minimum over
// colliders of a per-collider result that does not depend on the order in
// which colliders are tried, so the fan returns the same number.
//
// Parameters:
//   reach_m         longest ray to be cast (the LIDAR range, 5 in Reach)
//   kMaxCandidates  colliders kept near the origin (16); beyond that every ray
//                   falls back to World::ray_hit_fraction
#pragma once

#include <array>
#include <span>

#include <LinearMath/btVector3.h>

class btCollisionObject;
struct btDbvtNode;

namespace bsg::envs {

class World;

class RayFan {
 public:
  static constexpr int kMaxCandidates = 16;

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

 private:
  struct Candidate {
    const btCollisionObject* object;
    const btDbvtNode* leaf;  // its broadphase box, as Bullet's rayTest sees it
  };

  const World& world_;
  btVector3 origin_;
  double longest_ray2_;  // squared length beyond which a ray takes the generic path
  std::span<const btCollisionObject* const> ignore_;
  std::array<Candidate, kMaxCandidates> candidates_{};
  int count_ = 0;
  bool overflow_ = false;
};

}  // namespace bsg::envs
