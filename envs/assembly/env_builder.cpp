#include "envs/assembly/env_builder.h"

#include <stdexcept>

#include "envs/agents/ant_agent.h"
#include "envs/assembly/assembled_env.h"
#include "envs/agents/ball_agent.h"
#include "envs/agents/car_agent.h"
#include "envs/tasks/circle_task.h"
#include "envs/agents/drone_agent.h"
#include "envs/description/env_parameters.h"
#include "envs/tasks/gather_task.h"
#include "envs/tasks/reach_task.h"
#include "envs/tasks/run_task.h"

namespace bsg::envs {
namespace {

AgentFactory agent_factory(const std::string& agent) {
  if (agent == "Ball") return make_ball_agent;
  if (agent == "Car") return make_car_agent;
  if (agent == "Drone") return make_drone_agent;
  if (agent == "Ant") return make_ant_agent;
  throw std::invalid_argument("env: agent=" + agent + ": unknown agent; valid: Ball, Car, Drone, Ant");
}

std::unique_ptr<Task> make_task(const EnvDescription& d, World& world, Agent& agent,
                                const EnvOptions& options) {
  if (d.task == "Circle") return std::make_unique<CircleTask>(world, agent, d);
  if (d.task == "Gather") return std::make_unique<GatherTask>(world, agent, d);
  if (d.task == "Reach") return std::make_unique<ReachTask>(world, agent, d, options.box_clock);
  if (d.task == "Run") return std::make_unique<RunTask>(world, agent, d);
  throw std::invalid_argument("env: task=" + d.task + ": unknown task; valid: Circle, Gather, Reach, Run");
}

}  // namespace

bool agent_has_lean_model(const std::string& agent) { return agent == "Car" || agent == "Ant"; }

WorldLayout parse_world_layout(const std::string& world) {
  if (world == "SmallRoom") return WorldLayout::kSmallRoom;
  if (world == "Octagon") return WorldLayout::kOctagon;
  if (world == "Plane200") return WorldLayout::kPlane200;
  throw std::invalid_argument("env: world=" + world + ": unknown world; valid: SmallRoom, Octagon, Plane200");
}

std::unique_ptr<Env> build_env(const EnvDescription& d, const EnvOptions& options) {
  check_env_description(d);
  if (options.physics == PhysicsModel::kLean && !agent_has_lean_model(d.agent)) {
    throw std::invalid_argument(d.name + ": the " + d.agent +
                                " has no lean physics model (only the Ant and the "
                                "Car have one); use physics: faithful");
  }
  auto world = std::make_unique<World>(parse_world_layout(d.world), d.frame_skip, d.time_step);
  AgentOptions agent_options;
  agent_options.power_upgrade = d.power_upgrade;
  agent_options.physics = options.physics;
  agent_options.clip_actions = d.clip_actions;
  std::unique_ptr<Agent> agent = agent_factory(d.agent)(*world, agent_options);
  std::unique_ptr<Task> task = make_task(d, *world, *agent, options);
  EnvSpec spec;
  spec.id = d.name;
  spec.agent = d.agent;
  spec.task = d.task;
  spec.max_episode_steps = d.max_episode_steps;
  spec.cost_limit = d.cost_limit;
  return std::make_unique<AssembledEnv>(std::move(spec), options, std::move(world),
                                        std::move(agent), std::move(task));
}

}  // namespace bsg::envs
