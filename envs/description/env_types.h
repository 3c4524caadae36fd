// The value types of an environment (design.md "Environments"): its spec,
// what a step returns, the options it is made with, a layout to reset to and
// the state it reports. Data only: no Bullet, no behaviour; the face
// (envs/env.h) and every room below it speak in these types.
//
// Parameters (EnvOptions, every field has a default):
//   box_clock  kEpisodePhase (default): the Reach Box's pivot angle is drawn at
//              every reset from the seeded RNG and held for the episode;
//              kSimulated: the angle advances 1 rad per simulated second, counted
//              over env steps since construction (docs/environments.md#moving-box, golden files).
//   physics    kFaithful (default): the agent's model as PyBullet builds it, link
//              for link (the golden tests pin it down);
//              kLean: a physically equivalent model that is cheaper to step:
//              bodies joined by fixed joints merged into one rigid body with the
//              combined mass, centre of mass and inertia, and motors that can
//              never apply a force left out; shapes, friction, contacts, solver
//              and sub-steps unchanged. Trajectories differ from faithful ones
//              only by rounding (which chaos amplifies); episode statistics
//              agree (tests/envs/lean_physics_statistics_test.cpp). Only the Ant
//              and the Car have a lean model (ant_agent.h, car_agent.h); make()
//              rejects kLean for the others rather than quietly building their
//              faithful model.
#pragma once

#include <array>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "common/physics_model.h"

namespace bsg::envs {

// The physics model is the run config's type too (common/physics_model.h).
using bsg::PhysicsModel;
using bsg::parse_physics_model;

using Vec3 = std::array<double, 3>;
using Quat = std::array<double, 4>;  // [x, y, z, w], base-to-world (PyBullet order)

// What a learner needs to know about an environment (docs/environments.md#the-sixteen-environments).
struct EnvSpec {
  std::string id;             // e.g. "SafetyBallCircle-v0"
  std::string agent;          // "Ball", "Car", "Drone", "Ant"
  std::string task;           // "Circle", "Gather", "Reach", "Run"
  int observation_dim = 0;
  int action_dim = 0;
  int max_episode_steps = 0;  // truncation (gym TimeLimit)
  double cost_limit = 0;      // d of the report's Table 3 (docs/environments.md#the-sixteen-environments), per episode
  double action_low = -1;     // declared action bounds (docs/environments.md#one-step)
  double action_high = 1;
  double observation_bound = 1000;  // declared observation space ±1000 (never clipped)
  // The names of the task's cost terms, in the order of StepResult::cost_terms
  // (which every step reports in full), so that a learner can check which
  // terms a constraint sums before it takes a step.
  std::vector<std::string> cost_term_names;
};

// One named cost component, like the original's info keys (docs/environments.md#tasks):
// cost_outside_bounds, cost_velocity_violation, cost_collisions,
// number_collisions, cost_gathered_bombs, cost_out_of_range. Every term of
// the task is reported at every step (0 when not violated; the original omits
// some keys in that case).
struct CostTerm {
  std::string_view name;
  double value = 0;
};

// What a training-time decorator (envs/saute_env.h, envs/early_terminated_env.h) gives the
// learner in place of the environment's own reward and episode end. The rest of a StepResult
// stays the environment's, so that logs and evaluations report its true return and cost.
struct LearnerSignal {
  double reward = 0;          // the learner's reward (Saute's unsafe reward once a budget is spent)
  bool terminated = false;    // the learner's episode ends here; the environment's would go on
  bool budget_spent = false;  // some cost budget is spent at this step
};

struct StepResult {
  std::span<const double> observation;
  double reward = 0;
  double cost = 0;         // info["cost"], always 0 or 1
  bool terminated = false; // the agent died, or Gather collected every apple
  bool truncated = false;  // max_episode_steps reached without termination
  std::span<const CostTerm> cost_terms;
  std::optional<LearnerSignal> learner;  // absent: the learner sees reward and terminated as they are

  // The component called `name`; throws std::out_of_range listing the names.
  double cost_term(std::string_view name) const;
};

enum class BoxClock { kEpisodePhase, kSimulated };


struct EnvOptions {
  BoxClock box_clock = BoxClock::kEpisodePhase;
  PhysicsModel physics = PhysicsModel::kFaithful;
};

// A layout to reset to instead of a sampled one (evaluation on fixed layouts,
// golden tests). reset_to() applies it in place of every random placement draw
// of docs/environments.md#tasks and then does the reset's single engine step (docs/environments.md#reset), exactly
// as a sampled reset does. Fields a task does not use must be left empty;
// fields a task needs must be given, except where "default" says otherwise.
struct BoxPlacement {
  Vec3 position{};       // circle centre c = bottom-face centre (docs/environments.md#moving-box)
  Quat orientation{0, 0, 0, 1};
  double phase = 0;      // φ: the pivot is c + 0.7·(sin(t+φ), cos(t+φ), 0)
};

struct Layout {
  Vec3 agent_position{};             // base COM
  Quat agent_orientation{0, 0, 0, 1};
  // Movable joints in the agent's own order (Ball: none). Default (empty): the
  // agent's own randomised reset angles (docs/environments.md#agents).
  std::vector<double> joint_positions;
  // Reach.
  std::optional<Vec3> goal;
  std::optional<BoxPlacement> box;
  std::vector<Vec3> zones;           // the 8 puddles (or the Drone's pillars)
  std::optional<double> d_prev;      // default: ‖goal − agent‖_xy at placement
  // Gather.
  std::vector<Vec3> apples;
  std::vector<Vec3> bombs;
  // Run. Default: Φ(agent position) = −60·‖p − (1000, 0)‖.
  std::optional<double> phi_prev;
};

// A read-only snapshot of the simulation for tests and diagnostics (not on the
// step path: it allocates).
struct BoxState {
  Vec3 position{};
  Quat orientation{0, 0, 0, 1};
  Vec3 linear_velocity{};
  Vec3 angular_velocity{};
  Vec3 pivot{};          // the constraint's world pivot P used for the last step
  double clock_seconds = 0;  // t used for that pivot
};

struct EnvState {
  int elapsed_steps = 0;
  Vec3 agent_position{};
  Quat agent_orientation{0, 0, 0, 1};
  Vec3 agent_linear_velocity{};
  Vec3 agent_angular_velocity{};
  std::vector<double> joint_positions;   // movable joints, agent order
  std::vector<double> joint_velocities;
  double agent_reward = 0;  // s_agent of docs/environments.md#agents for the last step
  bool alive = true;
  // Task fields, present for the tasks that have them.
  std::optional<Vec3> goal;
  std::optional<double> d_prev;
  std::optional<double> phi_prev;
  std::optional<BoxState> box;
  std::vector<bool> apples_active;
  std::vector<bool> bombs_active;
};
}  // namespace bsg::envs
