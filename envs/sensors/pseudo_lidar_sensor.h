// Pseudo-LIDAR (docs/environments.md#pseudo-lidar): no ray casting; for a list of objects, the bin of
// each object's bearing (clockwise from world +y) holds 1 − δ/L for the
// nearest object within range L. World-aligned, never rotated with the agent.
//
// Parameters:
//   bins      Gather 16, Reach 24
//   range_m   Gather 10 (= env_dim), Reach 5 (= env_dim/2)
#pragma once

#include <span>

#include <LinearMath/btVector3.h>

namespace bsg::envs {

class PseudoLidarSensor {
 public:
  PseudoLidarSensor(int bins, double range_m);

  int bins() const { return bins_; }
  double range_m() const { return range_m_; }

  // Writes bins() values for the objects' xy positions seen from `agent`.
  void measure(const btVector3& agent, std::span<const btVector3> objects,
               std::span<double> out) const;

  // The bin of an object at `object` seen from `agent`; β = 2π maps to bin 0
  // (the original raises an index error there, docs/environments.md#pseudo-lidar).
  int bin_of(const btVector3& agent, const btVector3& object) const;

 private:
  int bins_;
  double range_m_;
};

}  // namespace bsg::envs
