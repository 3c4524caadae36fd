// Bullet's ray test of one box as PyBullet runs it (rayTestSingle with
// kF_UseGjkConvexCastRaytest), without GJK: the same conservative advancement
// (btGjkConvexCast), with the point-to-box distance in closed form.
//
// Bullet casts a point (a sphere of radius 0 and margin 0) along the ray r =
// to − from. GJK gives the distance from the point to the box's core (half
// extents less the collision margin) minus the margin, i.e. the distance to the
// box rounded by a sphere of radius = margin, and the unit normal from the
// core's closest point towards the point. From λ = 0 the cast steps
// λ ← λ − dist/(r·n) until dist <= kGjkCastRadius_m, so a hit lands up to
// 1e-3 m before the rounded surface (up to ~2e-4 in fraction near edges and
// corners): an exact ray-box intersection would not match it. This file
// repeats those steps and every exit; only the closest point on the core comes
// from clamping instead of GJK, which agrees with it to rounding
// (tests/envs/physics/ray_box_cast_test.cpp measures how closely).
//
// What the closed form might not repeat exactly is left to Bullet
// (kUndecided): a ray that starts within kGjkCastRadius_m of the rounded box
// or inside it, a point nearer than kMinCoreDistance_m to the core (GJK's
// degenerate branches), a zero-length ray, a margin below kMinBoxMargin_m.
//
// Parameters (Bullet 3.24, double precision):
//   kGjkCastRadius_m         1e-3  btGjkConvexCast: a hit once dist <= radius
//   kGjkCastMaxIterations    64    btGjkConvexCast: no hit after more steps
//   kRayMinNormalLength2     1e-4  rayTestSingleInternal keeps hits with |n|² above it
//   kMinCoreDistance_m       1e-4  nearer to the core: kUndecided
//   kMinBoxMargin_m          5e-4  smaller margins: kUndecided
#pragma once

#include <LinearMath/btTransform.h>
#include <LinearMath/btVector3.h>

class btBoxShape;

namespace bsg::envs {

inline constexpr double kGjkCastRadius_m = 1e-3;
inline constexpr int kGjkCastMaxIterations = 64;
inline constexpr double kRayMinNormalLength2 = 1e-4;
// GJK treats |v|² < 1e-12 and |v|² <= ε² specially; the advancement never
// comes nearer to the core than margin − rounding, so this bound (well above
// those, well below the margin) only catches rays that start at or in a box.
inline constexpr double kMinCoreDistance_m = 1e-4;
inline constexpr double kMinBoxMargin_m = 5e-4;

// A box as the ray test sees it: a core box of half extents
// `core_half_extents_m` (btBoxShape::getHalfExtentsWithoutMargin, scaling
// included) placed by `transform` (box frame to world), rounded by `margin_m`.
struct RoundedBox {
  btTransform transform;
  btVector3 core_half_extents_m;
  double margin_m = 0;
};

// The rounded box of `shape` placed by `transform`.
RoundedBox rounded_box(const btBoxShape& shape, const btTransform& transform);

enum class RayBoxOutcome { kMiss, kHit, kUndecided };

struct RayBoxHit {
  RayBoxOutcome outcome = RayBoxOutcome::kUndecided;
  double fraction = 1;  // of from→to; meaningful for kHit
};

// The ray from→to against `box`: kHit with the fraction Bullet's rayTestSingle
// reports (before it compares it with the closest hit so far), kMiss if it
// reports none, kUndecided if only Bullet can say.
RayBoxHit cast_ray_at_box(const btVector3& from, const btVector3& to, const RoundedBox& box);

}  // namespace bsg::envs
