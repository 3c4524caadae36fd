// What a task marks in the arena without a body (docs/environments.md#obstacles):
// safety boundaries, the Circle's track, the goal zone, puddles, pillars,
// apples and bombs, as plain data for whoever draws or plots an environment
// (render/). Physics never sees these; the step path never builds them.
#pragma once

#include "envs/description/env_types.h"

namespace bsg::envs {

struct Marking {
  enum class Kind {
    kCircleTrack,     // Circle: the disc of radius 7 the agent should run along
    kSafetyBoundary,  // Circle's slabs at x = ±6, Run's lane edges at y = ±2: from `position` to `end`
    kGoalZone,        // Reach: disc of radius 1.3
    kPuddle,          // Reach: disc
    kPillar,          // Reach with the Drone: cylinder of `height`
    kApple,           // Gather: sphere
    kBomb,            // Gather: sphere
  };
  Kind kind = Kind::kGoalZone;
  Vec3 position{};     // centre of a disc, sphere or cylinder base; one end of a boundary
  Vec3 end{};          // the other end of a boundary
  double radius = 0;   // disc, sphere or cylinder radius [m]
  double height = 0;   // pillar height [m]
  bool active = true;  // apples and bombs: false once collected
};

}  // namespace bsg::envs
