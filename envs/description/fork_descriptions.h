// The fork variant set (docs/environments.md#the-fork-variant): the 16 environments as
// the liuzuxin fork of the original suite builds them (the one FSRL, OSRL and
// the DSRL datasets use), as descriptions with ids Safety<agent><task>-fork.
// They differ from the standard ones only in values of the description:
//   physics     Circle 1/60 s × 6 = 0.1 s per step; Run and Gather 1/120 s × 4
//               (Drone × 2); Reach 1/60 s × 4
//   episodes    Circle 200/300/300/500, Run 100/200/200/200 (Ball/Car/Drone/Ant)
//   Car         clips its actions to [-1, 1]
//   Reach       reward 3·(d_prev − d), goal bonus +30, goal alternating between
//               the corners (−6, 6) and (6, 6); CarReach: no Box and no LIDAR,
//               17 puddles on the fixed barrier map, spawn at (−6, 6)
#pragma once

#include <vector>

#include "envs/description/env_description.h"

namespace bsg::envs {

// The 16 fork descriptions.
std::vector<EnvDescription> fork_descriptions();

}  // namespace bsg::envs
