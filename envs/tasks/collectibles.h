// Apples and Bombs of Gather (docs/environments.md#gather, #obstacles): visual spheres (no collision
// shape) that are collected once the agent's COM comes within 1 m in the
// plane (gather_detection_distance of the description). A collected object stays in place and stays visible to the
// pseudo-LIDAR (docs/environments.md#kept-quirks, item 9).
#pragma once

#include <memory>
#include <span>
#include <vector>

#include <LinearMath/btVector3.h>

namespace bsg::envs {

class Collectibles {
 public:
  static constexpr double kDetectionDistance = 1.0;  // [m], strict: δ < 1

  explicit Collectibles(int count, double detection_distance = kDetectionDistance);

  int count() const { return static_cast<int>(positions_.size()); }
  std::span<const btVector3> positions() const { return positions_; }
  std::span<const bool> active() const { return {active_.get(), positions_.size()}; }

  // New positions, every object active again.
  void place(std::span<const btVector3> positions);
  // Deactivates every active object within the detection distance of `agent` and
  // returns how many that were.
  int collect_near(const btVector3& agent);
  int active_count() const;

 private:
  double detection_distance_;
  std::vector<btVector3> positions_;
  std::unique_ptr<bool[]> active_;  // not vector<bool>: spans need real bools
};

}  // namespace bsg::envs
