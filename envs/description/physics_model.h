// The two models of an agent's bodies (EnvOptions::physics, env_types.h), as
// configs and the command line spell them: faithful (PyBullet's model, link
// for link) and lean (fixed joints merged; the Ant and the Car only).
#pragma once

#include <string_view>

namespace bsg::envs {

enum class PhysicsModel { kFaithful, kLean };

// "faithful" or "lean"; parse_physics_model throws std::invalid_argument naming
// the bad value and the valid ones.
std::string_view to_string(PhysicsModel model);
PhysicsModel parse_physics_model(std::string_view name);

}  // namespace bsg::envs
