// The public face of the environments (design.md "Environments"): an `Env`
// with spec(), reset(seed) and step(action), made by id from the registry.
// This header includes no Bullet header, so learners depend on it alone.
// Its value types (spec, step result, options, layout, state) are in
// envs/description/env_types.h; the assembly room implements Env.
//
// Threading: an Env is not thread-safe; use one per thread. Observations and
// cost terms returned by reset()/step() are views into buffers the Env owns,
// valid until its next reset()/step() call.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "envs/description/env_description.h"
#include "envs/description/env_parameters.h"
#include "envs/description/env_types.h"

namespace bsg::envs {

class Env {
 public:
  virtual ~Env() = default;

  virtual const EnvSpec& spec() const = 0;

  // Reseeds the environment's RNG with `seed`, then resets (docs/environments.md#reset).
  virtual std::span<const double> reset(std::uint64_t seed) = 0;
  // Resets and keeps drawing from the current RNG stream (the RNG starts from
  // seed 0 if reset(seed) was never called).
  virtual std::span<const double> reset() = 0;
  // Resets to a given layout instead of sampling one.
  virtual std::span<const double> reset_to(const Layout& layout) = 0;
  // The layout placed by the last reset (sampled or injected).
  virtual const Layout& layout() const = 0;

  // One step (docs/environments.md#one-step). Throws std::invalid_argument if the action size is
  // not spec().action_dim or an entry is NaN or infinite, and std::logic_error
  // if called before the first reset. Out-of-range entries are treated as the
  // original does (clipped by Ball, Drone, Ant; not by the Car).
  virtual StepResult step(std::span<const double> action) = 0;

  virtual EnvState state() const = 0;
  // Teleports the agent's base COM (orientation and velocities unchanged), as
  // PyBullet's resetBasePositionAndOrientation; for oracle tests.
  virtual void teleport_agent(const Vec3& com_position) = 0;
};

// Makes a registered environment; throws std::invalid_argument listing every
// valid id if `id` is unknown, or naming the agent if options.physics is kLean
// and the agent has no lean model.
std::unique_ptr<Env> make(const std::string& id, const EnvOptions& options = {});

// Builds any description, standard or custom (env_description.h); throws
// std::invalid_argument with one line naming the key at fault.
std::unique_ptr<Env> make(const EnvDescription& description, const EnvOptions& options = {});

// The description registered as `id` with `overrides` applied and checked
// (env_parameters.h); throws std::invalid_argument naming the id or the key.
EnvDescription describe(const std::string& id, const EnvOverrides& overrides = {});

// Every registered id, sorted.
std::vector<std::string> registered_ids();

// True if make(id) accepts PhysicsModel::kLean; throws like make() for an unknown id.
bool has_lean_model(const std::string& id);
bool has_lean_model(const EnvDescription& description);

}  // namespace bsg::envs
