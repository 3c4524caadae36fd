#include "envs/physics/planar_geometry.h"

#include <cmath>

namespace bsg::envs {

double planar_distance(const btVector3& a, const btVector3& b) {
  const double dx = a.x() - b.x();
  const double dy = a.y() - b.y();
  return std::sqrt(dx * dx + dy * dy);
}

}  // namespace bsg::envs
