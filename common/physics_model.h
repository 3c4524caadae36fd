// The two models of an agent's bodies, as the run config (`physics:`), the
// command line (--physics) and the environments (EnvOptions::physics,
// envs/description/env_types.h) all name them: one type for all three.
//   faithful  the agent as PyBullet builds it, link for link (the golden tests pin it down);
//   lean      bodies joined by fixed joints merged into one rigid body (the Ant and the Car only).
#pragma once

#include <array>
#include <string_view>

namespace bsg {

enum class PhysicsModel { kFaithful, kLean };
// In enumerator order (the config table maps names to values by position).
inline constexpr std::array<std::string_view, 2> kPhysicsModelNames = {"faithful", "lean"};

// "faithful" or "lean"; parse_physics_model throws std::invalid_argument naming
// the bad value and the valid ones.
std::string_view to_string(PhysicsModel model);
PhysicsModel parse_physics_model(std::string_view name);

}  // namespace bsg
