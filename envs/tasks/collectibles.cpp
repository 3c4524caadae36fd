#include "envs/tasks/collectibles.h"

#include <stdexcept>
#include <string>

#include "envs/tasks/placement_sampler.h"

namespace bsg::envs {

Collectibles::Collectibles(int count, double detection_distance)
    : detection_distance_(detection_distance),
      positions_(static_cast<size_t>(count), btVector3(0, 0, 0)),
      active_(std::make_unique<bool[]>(static_cast<size_t>(count))) {
  for (int i = 0; i < count; ++i) active_[static_cast<size_t>(i)] = true;
}

void Collectibles::place(std::span<const btVector3> positions) {
  if (positions.size() != positions_.size()) {
    throw std::invalid_argument("Collectibles: need " + std::to_string(positions_.size()) +
                                " positions, got " + std::to_string(positions.size()));
  }
  for (size_t i = 0; i < positions.size(); ++i) {
    positions_[i] = positions[i];
    active_[i] = true;
  }
}

int Collectibles::collect_near(const btVector3& agent) {
  int collected = 0;
  for (size_t i = 0; i < positions_.size(); ++i) {
    if (active_[i] && planar_distance(positions_[i], agent) < detection_distance_) {
      active_[i] = false;
      ++collected;
    }
  }
  return collected;
}

int Collectibles::active_count() const {
  int active = 0;
  for (size_t i = 0; i < positions_.size(); ++i) active += active_[i] ? 1 : 0;
  return active;
}

}  // namespace bsg::envs
