#include "envs/tasks/zone_obstacles.h"

#include <stdexcept>
#include <string>

#include "envs/tasks/placement_sampler.h"

namespace bsg::envs {

ZoneObstacles::ZoneObstacles(ZoneKind kind, int count, double radius)
    : kind_(kind),
      radius_(radius),
      positions_(static_cast<size_t>(count), btVector3(0, 0, 0)) {}

void ZoneObstacles::place(std::span<const btVector3> positions) {
  if (positions.size() != positions_.size()) {
    throw std::invalid_argument("ZoneObstacles: need " + std::to_string(positions_.size()) +
                                " positions, got " + std::to_string(positions.size()));
  }
  positions_.assign(positions.begin(), positions.end());
}

int ZoneObstacles::collisions(const btVector3& agent, double agent_radius) const {
  int count = 0;
  for (const btVector3& zone : positions_) {
    if (planar_distance(agent, zone) - agent_radius - radius_ <= 0) ++count;
  }
  return count;
}

}  // namespace bsg::envs
