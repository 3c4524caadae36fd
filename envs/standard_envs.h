// The 16 standard environments as the programs above the face see them
// (`bsg envs --picture`, the Python module's render_fps): their descriptions,
// in the registry's order, and the simulated duration of one of their steps.
// The descriptions are data of envs/description/; this header is the face's
// door to them, so that cli/ and python/src/ include only files in envs/.
#pragma once

#include "envs/description/standard_descriptions.h"

namespace bsg::envs {

// Simulated seconds per environment step of every standard id: 4 engine steps
// of 1/240 s (Circle, Run, Gather) or one of 1/60 s (Reach). The physics'
// own constant is World::kEnvStepSeconds (tests/envs/standard_envs_test.cpp
// holds the two equal); one frame per step plays in real time at 60 fps.
inline constexpr double kStandardEnvStepSeconds = 1.0 / 60.0;

}  // namespace bsg::envs
