#include "envs/physics/ray_box_cast.h"

#include <cmath>

#include <BulletCollision/CollisionShapes/btBoxShape.h>

namespace bsg::envs {
namespace {

// What GJK (btGjkPairDetector with the point as A and the box as B, no
// penetration solver) reports for a point against the box whose frame has
// been moved to `box_origin`.
struct Separation {
  bool decided;       // false: too near the core for the closed form
  double distance_m;  // |v| − margin: to the rounded box, negative inside it
  btVector3 normal;   // v/|v|
};

Separation separation(const btVector3& point, const btVector3& box_origin,
                      const RoundedBox& box) {
  const btMatrix3x3& basis = box.transform.getBasis();
  // The point in the box frame, basisᵀ(p − o), and how far it lies outside
  // the core along each axis: p minus its closest point on the core.
  const btVector3 local = (point - box_origin) * basis;
  btVector3 outside(0, 0, 0);
  for (int k = 0; k < 3; ++k) {
    const double half = box.core_half_extents_m[k];
    if (local[k] > half) {
      outside[k] = local[k] - half;
    } else if (local[k] < -half) {
      outside[k] = local[k] + half;
    }
  }
  // v: GJK's separating vector, from the core's closest point to the point.
  const btVector3 v = basis * outside;
  const double length2 = v.length2();
  if (!(length2 >= kMinCoreDistance_m * kMinCoreDistance_m)) {
    return {false, 0, btVector3(0, 0, 0)};
  }
  // As GJK: normal = v / |v|, distance = |v| − margin (margin of A is 0).
  const double inverse_length = 1 / std::sqrt(length2);
  return {true, 1 / inverse_length - box.margin_m, v * inverse_length};
}

constexpr RayBoxHit kMissed{RayBoxOutcome::kMiss, 1};
constexpr RayBoxHit kUnknown{RayBoxOutcome::kUndecided, 1};

}  // namespace

RoundedBox rounded_box(const btBoxShape& shape, const btTransform& transform) {
  return {transform, shape.getHalfExtentsWithoutMargin(), shape.getMargin()};
}

RayBoxHit cast_ray_at_box(const btVector3& from, const btVector3& to, const RoundedBox& box) {
  if (!(box.margin_m >= kMinBoxMargin_m)) return kUnknown;
  // r = linVelA − linVelB; the box's "velocity" is exactly 0 (from = to = its pose).
  const btVector3 r = to - from;
  if (!(r.length2() > 0)) return kUnknown;
  const btVector3& origin = box.transform.getOrigin();

  // λ = 0: GJK at the ray's start, the box at its own pose.
  const Separation start = separation(from, origin, box);
  if (!start.decided || !(start.distance_m > kGjkCastRadius_m)) return kUnknown;

  // btPointCollector keeps only a report nearer than the nearest so far:
  // (distance, normal) below are that record, as the cast reads it.
  double distance = start.distance_m;
  btVector3 normal = start.normal;
  double lambda = 0;
  double last_lambda = 0;
  int iterations = 0;
  while (distance > kGjkCastRadius_m) {
    if (++iterations > kGjkCastMaxIterations) return kMissed;
    // Conservative advancement: λ ← λ − dist/(r·n).
    lambda -= distance / r.dot(normal);
    if (lambda > 1 || lambda < 0 || lambda <= last_lambda) return kMissed;
    last_lambda = lambda;
    // Both shapes' origins interpolated as btTransform origins are
    // (setInterpolate3), the box's between two equal poses.
    btVector3 point;
    point.setInterpolate3(from, to, lambda);
    btVector3 box_origin;
    box_origin.setInterpolate3(origin, origin, lambda);
    const Separation next = separation(point, box_origin, box);
    if (!next.decided) return kUnknown;
    if (next.distance_m < distance) {
      distance = next.distance_m;
      normal = next.normal;
    }
    // Penetration: a hit at this λ, without the direction test below.
    if (distance < 0) return {RayBoxOutcome::kHit, lambda};
  }
  // No time of impact for motion away from the normal (allowed penetration 0).
  if (normal.dot(r) >= -0.0) return kMissed;
  // rayTestSingleInternal's test of the normal: a unit normal always passes.
  if (!(normal.length2() > kRayMinNormalLength2)) return kMissed;
  return {RayBoxOutcome::kHit, lambda};
}

}  // namespace bsg::envs
