// A task (design.md "Environments"): places the agent, goals and obstacles at
// reset, computes reward and cost, writes the sensor and task part of the
// observation and decides whether its goal ends the episode (docs/environments.md#tasks). Tasks
// see the agent only through the Agent interface.
#pragma once

#include <memory>
#include <span>
#include <string>
#include <vector>

#include "envs/agents/agent.h"
#include "common/random.h"
#include "envs/description/env_types.h"
#include "envs/tasks/marking.h"
#include "envs/physics/world.h"

namespace bsg::envs {

// What one step of a task yields (docs/environments.md#one-step, items 6, 7 and 9).
struct TaskOutcome {
  double reward = 0;
  double cost = 0;            // min(1, sum of the cost terms)
  bool ends_episode = false;  // Gather: every apple collected
};

class Task {
 public:
  virtual ~Task() = default;

  // Sensor entries (in attachment order) plus task entries written after the
  // agent's part of the observation.
  virtual int observation_dim() const = 0;
  // The cost components of the last evaluate(), in a fixed order.
  virtual std::span<const CostTerm> cost_terms() const = 0;

  // Draws a layout (docs/environments.md#tasks). The agent has just been reset; its
  // joint angles are already drawn and not part of the task's draws.
  virtual void sample_layout(Rng& rng, Layout& layout) = 0;
  // Places the agent's base, the goal and the obstacles as `layout` says and
  // restores the task's per-episode state; throws std::invalid_argument naming
  // a missing or malformed field. `clock_seconds` is the Box clock t.
  virtual void place(const Layout& layout, double clock_seconds) = 0;
  // Obstacle movement before the engine step (docs/environments.md#one-step, item 3).
  virtual void before_physics(double /*clock_seconds*/) {}
  // Reward, cost and goal logic after the engine step (may draw a new goal).
  virtual TaskOutcome evaluate(Rng& rng) = 0;
  virtual void write_observation(std::span<double> out) const = 0;
  // Task fields of EnvState.
  virtual void write_state(EnvState& /*state*/) const {}
  // Appends what the task marks without a body (marking.h), for drawing; not
  // on the step path.
  virtual void add_markings(std::vector<Marking>& /*out*/) const {}
};

}  // namespace bsg::envs
