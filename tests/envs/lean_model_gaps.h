// How far a lean model strays from the faithful one (env.h, PhysicsModel), for
// the lean Ant and lean Car model tests: the gap between two orientations, and
// over a trajectory (both environments reset with the same seed and driven by
// the same actions) the largest differences of the agent's COM position and
// velocity and of the joint angles.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <LinearMath/btMatrix3x3.h>

#include "common/random.h"
#include "envs/env.h"

namespace bsg::envs {

// Sum over the rows of the distance between two rotation matrices' rows.
inline double rotation_gap(const btMatrix3x3& a, const btMatrix3x3& b) {
  double gap = 0;
  for (int row = 0; row < 3; ++row) gap += (a.getRow(row) - b.getRow(row)).length();
  return gap;
}

struct TrajectoryGap {
  double position = 0;  // agent COM [m]
  double velocity = 0;  // agent COM linear velocity [m/s]
  double joints = 0;    // joint angles [rad]
};

// Largest gaps over `steps` steps of uniform random actions in [-1, 1] (from
// Rng(seed + 1)), or of zero actions.
inline TrajectoryGap largest_lean_gap(const std::string& id, int steps, std::uint64_t seed, bool random_actions) {
  const auto faithful = make(id);
  const auto lean = make(id, {.physics = PhysicsModel::kLean});
  faithful->reset(seed);
  lean->reset(seed);
  Rng rng(seed + 1);
  std::vector<double> action(static_cast<size_t>(faithful->spec().action_dim), 0.0);
  TrajectoryGap gap;
  for (int t = 0; t < steps; ++t) {
    if (random_actions) {
      for (double& x : action) x = uniform(rng, -1, 1);
    }
    faithful->step(action);
    lean->step(action);
    const EnvState f = faithful->state();
    const EnvState l = lean->state();
    for (int axis = 0; axis < 3; ++axis) {
      gap.position = std::max(gap.position, std::abs(f.agent_position[axis] - l.agent_position[axis]));
      gap.velocity = std::max(gap.velocity,
                              std::abs(f.agent_linear_velocity[axis] - l.agent_linear_velocity[axis]));
    }
    for (size_t j = 0; j < f.joint_positions.size(); ++j) {
      gap.joints = std::max(gap.joints, std::abs(f.joint_positions[j] - l.joint_positions[j]));
    }
  }
  return gap;
}

}  // namespace bsg::envs
