// Random placement of goals and obstacles in the SmallRoom (docs/environments.md#worlds, #placement-sampling):
// uniform points in the square [−7, 7]² on the ground and the original's
// rejection sampler `generate_obstacles_init_pos`, with an attempt guard in
// place of the original's guard that never fires (docs/environments.md#kept-quirks, item 14).
#pragma once

#include <optional>
#include <vector>

#include <LinearMath/btVector3.h>

#include "common/random.h"
#include "envs/physics/planar_geometry.h"  // planar_distance, which the placement rule uses

namespace bsg::envs {

// Half-width of the SmallRoom's placement square: int(0.7·env_dim) = 7.
inline constexpr double kPlacementHalfWidth = 7.0;
inline constexpr long kMaxPlacementAttempts = 100000;

// (U(−w, w), U(−w, w), 0) with w = half_width: x drawn first.
btVector3 uniform_room_point(Rng& rng, double half_width = kPlacementHalfWidth);

// `count` positions, in acceptance order. A draw q is rejected if
// ‖q − agent‖_xy < agent_clearance; it is accepted iff its 3-d distance to every
// position accepted so far (and to `goal`, if given) is > pairwise_clearance.
// Draws in the square of `half_width`. Throws std::runtime_error after
// kMaxPlacementAttempts draws.
std::vector<btVector3> sample_obstacle_positions(Rng& rng, int count, const btVector3& agent,
                                                 const std::optional<btVector3>& goal,
                                                 double pairwise_clearance,
                                                 double agent_clearance,
                                                 double half_width = kPlacementHalfWidth);

}  // namespace bsg::envs
