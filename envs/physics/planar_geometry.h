// Distances in the ground plane, shared by the tasks' placement and the
// pseudo-lidar (docs/environments.md#planar-distances).
#pragma once

#include <LinearMath/btVector3.h>

namespace bsg::envs {

// ‖a − b‖ in the plane, as NumPy's norm: sqrt(dx² + dy²) (docs/environments.md#planar-distances).
double planar_distance(const btVector3& a, const btVector3& b);

}  // namespace bsg::envs
