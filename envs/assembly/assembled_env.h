// The one Env implementation: a World, an Agent and a Task put together by the
// builder (env_builder.h), stepping and resetting as the original's
// EnvironmentBuilder does (docs/environments.md#one-step, #reset). The step path allocates nothing:
// the observation buffer and the task's cost terms are preallocated.
#pragma once

#include <memory>
#include <vector>

#include "envs/agents/agent.h"
#include "common/random.h"
#include "envs/env.h"
#include "envs/tasks/task.h"
#include "envs/physics/world.h"

namespace bsg::envs {

// The state of one agent and its task (EnvState), as Env::state() reports it.
EnvState snapshot_state(const Agent& agent, const Task& task, int elapsed_steps);

class AssembledEnv final : public Env {
 public:
  // `spec.observation_dim` is computed here from the agent and the task.
  AssembledEnv(EnvSpec spec, const EnvOptions& options, std::unique_ptr<World> world,
               std::unique_ptr<Agent> agent, std::unique_ptr<Task> task);

  const EnvSpec& spec() const override { return spec_; }
  std::span<const double> reset(std::uint64_t seed) override;
  std::span<const double> reset() override;
  std::span<const double> reset_to(const Layout& layout) override;
  const Layout& layout() const override { return layout_; }
  StepResult step(std::span<const double> action) override;
  EnvState state() const override;
  void teleport_agent(const Vec3& com_position) override;

  // For benchmarks: the world and agent alone, to time raw physics of the same scene.
  World& world() { return *world_; }
  Agent& agent() { return *agent_; }

  // Read-only views for drawing (scene.h); not on the step path.
  const World& world() const { return *world_; }
  const Agent& agent() const { return *agent_; }
  std::vector<Marking> markings() const;

 private:
  // The shared reset path of docs/environments.md#reset; `injected` replaces the task's draws.
  std::span<const double> reset_impl(const Layout* injected);
  // The Box clock t (docs/environments.md#moving-box): steps since construction × 1/60 in
  // kSimulated mode; 0 in kEpisodePhase mode, where the drawn phase holds.
  double clock_seconds() const;
  void check_action(std::span<const double> action) const;
  void write_observation();

  EnvSpec spec_;
  EnvOptions options_;
  // Declared first so that it is destroyed last: agent and task borrow from it.
  std::unique_ptr<World> world_;
  std::unique_ptr<Agent> agent_;
  std::unique_ptr<Task> task_;
  Rng rng_{0};
  Layout layout_;
  std::vector<double> observation_;
  int elapsed_steps_ = 0;
  long long steps_since_construction_ = 0;
  bool has_reset_ = false;
};

}  // namespace bsg::envs
