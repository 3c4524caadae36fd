#include "envs/tasks/placement_sampler.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace bsg::envs {

btVector3 uniform_room_point(Rng& rng, double half_width) {
  const double x = uniform(rng, -half_width, half_width);
  const double y = uniform(rng, -half_width, half_width);
  return {x, y, 0};
}

std::vector<btVector3> sample_obstacle_positions(Rng& rng, int count, const btVector3& agent,
                                                 const std::optional<btVector3>& goal,
                                                 double pairwise_clearance,
                                                 double agent_clearance, double half_width) {
  std::vector<btVector3> accepted;  // the goal (if any) first, as in the original
  if (goal) accepted.push_back(*goal);
  const size_t first = accepted.size();
  long attempts = 0;
  while (accepted.size() - first < static_cast<size_t>(count)) {
    if (++attempts > kMaxPlacementAttempts) {
      throw std::runtime_error(
          "obstacle placement: no room for " + std::to_string(count) + " obstacles with clearance " +
          std::to_string(pairwise_clearance) + " m after " + std::to_string(kMaxPlacementAttempts) +
          " draws (fewer objects or a smaller spacing in the environment's description)");
    }
    const btVector3 q = uniform_room_point(rng, half_width);
    if (planar_distance(q, agent) < agent_clearance) continue;
    bool clear = true;
    for (const btVector3& other : accepted) {
      // 3-d norm; every z here is 0 (docs/environments.md#placement-sampling).
      if ((q - other).length() <= pairwise_clearance) {
        clear = false;
        break;
      }
    }
    if (clear) accepted.push_back(q);
  }
  return {accepted.begin() + static_cast<std::ptrdiff_t>(first), accepted.end()};
}

}  // namespace bsg::envs
