// The Drone (docs/environments.md#drone, class `Drone` of the original): an AscTec-Hummingbird-
// like quadcopter (URDF loaded with global scaling 2) whose four rotors are real
// spinning links driven by velocity motors. Each step the action sets the rotor
// speed targets ω*_i = d_i·ω_h·(1 + 0.1·a_i), and a thrust computed from the
// *target* speed pushes every rotor along its own z axis. It dies when it rolls
// past 90°.
//
// Parameters (docs/environments.md#agents, #drone; none depends on the task, the Drone has no
// "power upgrade"):
//   rotor directions d       (+1, -1, +1, -1)
//   hover speed ω_h          461.5227869527166 rad/s (docs/environments.md#drone)
//   speed range              ±10 % of ω_h per unit action (actions clipped to [-1, 1])
//   rotor motor force        23.444 (max impulse 23.444/60 per internal step, docs/environments.md#motors-forces-and-contacts)
//   joint velocity clamp     1000 rad/s
//   initial position         (0, 0, 0.17), identity orientation
//   collision radius         0.5 m; Run speed limit 1.5 m/s
//   LIDAR                    rotates with the drone, offset (0, 0, 0)
//
// colliders() lists the dummy base's (an empty shape, as PyBullet's importer
// makes it) and then links 0–4: the body box and rotors 0–3.
#pragma once

#include <memory>

#include "envs/agents/agent.h"

namespace bsg::envs {

// Hover speed ω_h = (2π/p)·sqrt((m·g/4)/(ρ·A)·(p/(k₁·D))^k₂) [rad/s] (docs/environments.md#drone),
// evaluated in double exactly as the original does.
double drone_hover_speed_rad_per_s();

// Rotor thrust T(ω, v₀) = ρ·A·(n² − n·v₀)·(k₁·D/p)^k₂ with n = ω·p/(2π) [N]
// for rotor speed ω [rad/s] and axial inflow speed v₀ [m/s] (docs/environments.md#drone).
double drone_thrust_newton(double rotor_speed_rad_per_s, double inflow_speed_m_per_s);

std::unique_ptr<Agent> make_drone_agent(World& world, const AgentOptions& options);

}  // namespace bsg::envs
