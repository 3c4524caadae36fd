// An agent: builds its bodies and joints in a World, turns an action into
// forces or motor targets, writes its own part of the observation and tells
// its pose and velocity (docs/environments.md#agents). Tasks and sensors see agents only
// through this interface.
#pragma once

#include <span>

#include <LinearMath/btQuaternion.h>
#include <LinearMath/btVector3.h>

#include "common/random.h"
#include "envs/description/env_types.h"

class btCollisionObject;

namespace bsg::envs {

class World;

// What an agent needs to know about the task it is built for.
struct AgentOptions {
  // Reach and Gather give the Car and the Ant stronger motors (docs/environments.md#agents "power upgrade").
  bool power_upgrade = false;
  // Faithful or lean model (env.h); only agents registered with a lean model see kLean.
  PhysicsModel physics = PhysicsModel::kFaithful;
  // The Car clips its actions to [-1, 1] as the others do (the fork's Car;
  // the original's does not, docs/environments.md#kept-quirks, item 4).
  bool clip_actions = false;
};

// Per-agent constants of docs/environments.md#agents that tasks and sensors use.
struct AgentTraits {
  int action_dim = 0;
  int observation_dim = 0;  // the agent's own part of the observation
  btVector3 initial_position{0, 0, 0};  // base COM at construction
  double initial_yaw = 0;               // yaw_init: π for the Car, 0 otherwise
  double collision_radius = 0;          // for Puddle/Pillar costs (Reach)
  double run_speed_limit = 0;           // Run task's ‖v_xy‖ threshold [m/s]
  bool sensor_rotates = false;          // LIDAR turns with the base (Car, Drone)
  btVector3 sensor_offset{0, 0, 0};     // LIDAR origin in the base frame
};

class Agent {
 public:
  virtual ~Agent() = default;

  virtual const AgentTraits& traits() const = 0;

  // Agent-specific part of a reset (docs/environments.md#agents, #reset, step 3): velocities to zero,
  // base back to its initial pose, joint randomisation drawn from `rng`.
  virtual void reset(Rng& rng) = 0;
  // Teleports the base COM and orientation (PyBullet's
  // resetBasePositionAndOrientation); velocities are left as they are.
  virtual void set_base_pose(const btVector3& com_position, const btQuaternion& orientation) = 0;
  // Sets every movable joint's angle, in the agent's own joint order, with zero
  // joint velocity (used to inject a recorded layout).
  virtual void set_joint_positions(std::span<const double> joint_positions) = 0;
  virtual int movable_joint_count() const = 0;

  // Applies an action of traits().action_dim finite entries (checked by the
  // caller): forces or motor targets that act during the next World::step().
  virtual void apply_action(std::span<const double> action) = 0;
  // Post-step bookkeeping from the last internal step's contacts (Ant feet,
  // Drone ground contacts); not called after the reset's engine step (docs/environments.md#reset).
  virtual void after_step() {}

  // Writes traits().observation_dim entries.
  virtual void write_observation(std::span<double> out) const = 0;
  // s_agent of docs/environments.md#agents for the last applied action and step.
  virtual double specific_reward() const = 0;
  virtual bool alive() const = 0;

  // Base COM position, base-to-world orientation, world-frame velocities.
  virtual btVector3 position() const = 0;
  virtual btQuaternion orientation() const = 0;
  virtual btVector3 linear_velocity() const = 0;
  virtual btVector3 angular_velocity() const = 0;
  // Movable joints in the agent's own order (empty for the Ball).
  virtual void joint_state(std::span<double> positions, std::span<double> velocities) const = 0;

  // The agent's colliders: excluded from its own LIDAR, checked for contact
  // with the Reach Box.
  virtual std::span<const btCollisionObject* const> colliders() const = 0;
};

}  // namespace bsg::envs
