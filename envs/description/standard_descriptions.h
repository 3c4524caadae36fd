// The 16 standard environments as descriptions (docs/environments.md#the-sixteen-environments):
// Safety<agent><task>-v0 for the four agents on the four tasks, every value
// the original's. A custom combination starts from the same function.
#pragma once

#include <string>
#include <vector>

#include "envs/description/env_description.h"

namespace bsg::envs {

// The original's description of agent on task, named Safety<agent><task>-v0.
// Throws std::invalid_argument naming an unknown agent or task.
EnvDescription standard_description(const std::string& agent, const std::string& task);

// Every standard description, in the order of the registry's agents and tasks.
std::vector<EnvDescription> standard_descriptions();

// Radius of a Reach zone type: puddle 1 m, pillar 0.45 m (docs/environments.md#obstacles).
double standard_zone_radius(const std::string& zone_type);

}  // namespace bsg::envs
