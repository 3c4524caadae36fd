// Several robots in one arena (docs/multi_agent.md#several-robots-on-circle): one
// world, one agent per robot, each with its own copy of the single-agent task
// (its reward and cost terms, e.g. Circle's), plus a cost term
// cost_agent_collisions, 1 while the robot touches another robot. The reset
// draws every robot's spawn from the task's own sampler in robot order,
// redrawing a robot closer than agent_spacing (planar) to one placed before it.
//
// Agent i observes its robot's single-agent observation (agent part, then task
// part), then, for every other robot j in order, (p_j − p_i)_xy / env_dim. Its
// reward and cost are its robot's (own) or the sums over robots (team); its
// cost is min(1, task cost + collision) before any sum. The global state is
// every robot's single-agent observation, robot order. The team terminates when
// a robot dies and truncates at max_episode_steps.
#pragma once

#include <memory>
#include <vector>

#include "common/random.h"
#include "envs/agents/agent.h"
#include "envs/assembly/multi_agent_buffers.h"
#include "envs/multi_agent_env.h"
#include "envs/physics/world.h"
#include "envs/tasks/marking.h"
#include "envs/tasks/task.h"

class btCollisionObject;

namespace bsg::envs {

// One robot: its agent and its task, built in the shared world.
struct Body {
  std::unique_ptr<Agent> agent;
  std::unique_ptr<Task> task;
};

class MultiBodyEnv final : public MultiAgentEnv {
 public:
  MultiBodyEnv(const MultiAgentDescription& description, std::unique_ptr<World> world,
               std::vector<Body> bodies);

  const MultiAgentSpec& spec() const override { return spec_; }
  std::span<const std::span<const double>> reset(std::uint64_t seed) override;
  std::span<const std::span<const double>> reset() override;
  std::span<const std::span<const double>> reset_to(std::span<const Layout> layouts) override;
  MultiAgentStepResult step(std::span<const std::span<const double>> actions) override;
  std::span<const double> global_state() const override { return buffers_.global_state(); }
  std::vector<EnvState> body_states() const override;

  // Read-only views for drawing (scene.h); not on the step path.
  const World& world() const { return *world_; }
  std::span<const btCollisionObject* const> robot_colliders() const { return all_colliders_; }
  const Agent& agent(int body) const { return *bodies_[body].agent; }
  std::vector<Marking> markings() const;

 private:
  std::span<const std::span<const double>> reset_impl(const std::vector<Layout>* injected);
  void sample_layouts(std::vector<Layout>& layouts);
  // Reach (MultiGoal): whether robot i's spawn and goal keep reach_spacing
  // from the hazards robot 0's layout placed for all.
  bool clear_of_shared_hazards(const Layout& robot, const Layout& first) const;
  bool touches_another_robot(size_t body) const;
  std::span<const std::span<const double>> observe();

  MultiAgentSpec spec_;
  const double agent_spacing_;
  const bool count_agent_collisions_;
  const bool shared_hazards_;    // Reach: robot 0's task holds the zones and Box for all
  const double hazard_spacing_;  // reach_spacing: spawn and goal to every hazard
  // Declared first so that it is destroyed last: agents and tasks borrow from it.
  std::unique_ptr<World> world_;
  std::vector<Body> bodies_;
  std::vector<const btCollisionObject*> all_colliders_;
  MultiAgentBuffers buffers_;
  std::vector<double> body_rewards_;
  std::vector<double> body_costs_;
  Rng rng_{0};
  int elapsed_steps_ = 0;
  bool has_reset_ = false;
};

// The spec of `description` built from its robots (observation and action
// dims from the agents and tasks).
MultiAgentSpec multi_body_spec(const MultiAgentDescription& description, const std::vector<Body>& bodies);

}  // namespace bsg::envs
