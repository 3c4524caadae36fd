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
#include "envs/assembly/limb_split_env.h"
#include "envs/assembly/multi_body_env.h"

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

namespace {

void require_model(const EnvDescription& d, const EnvOptions& options) {
  if (options.physics == PhysicsModel::kLean && !agent_has_lean_model(d.agent)) {
    throw std::invalid_argument(d.name + ": the " + d.agent +
                                " has no lean physics model (only the Ant and the "
                                "Car have one); use physics: faithful");
  }
}

std::unique_ptr<World> make_world(const EnvDescription& d) {
  return std::make_unique<World>(parse_world_layout(d.world), d.frame_skip, d.time_step);
}

std::unique_ptr<Agent> make_agent(const EnvDescription& d, World& world, const EnvOptions& options) {
  AgentOptions agent_options;
  agent_options.power_upgrade = d.power_upgrade;
  agent_options.physics = options.physics;
  agent_options.clip_actions = d.clip_actions;
  return agent_factory(d.agent)(world, agent_options);
}

}  // namespace

std::unique_ptr<Env> build_env(const EnvDescription& d, const EnvOptions& options) {
  check_env_description(d);
  require_model(d, options);
  auto world = make_world(d);
  std::unique_ptr<Agent> agent = make_agent(d, *world, options);
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

std::unique_ptr<MultiAgentEnv> build_multi_agent_env(const MultiAgentDescription& d,
                                                     const EnvOptions& options) {
  check_multi_agent_description(d);
  if (d.partition != "body") return std::make_unique<LimbSplitEnv>(d, build_env(d.env, options));
  require_model(d.env, options);
  auto world = make_world(d.env);
  std::vector<Body> bodies;
  for (int i = 0; i < d.bodies; ++i) {
    Body body;
    body.agent = make_agent(d.env, *world, options);
    if (d.env.task == "Reach" && i > 0) {
      // MultiGoal: robot 0's task holds the zones and the Box, placed once for all.
      EnvDescription own_goal_only = d.env;
      own_goal_only.zones = 0;
      own_goal_only.box = false;
      const auto* hazards = static_cast<const ReachTask*>(bodies.front().task.get());
      body.task = std::make_unique<ReachTask>(*world, *body.agent, own_goal_only, options.box_clock, hazards);
    } else {
      body.task = make_task(d.env, *world, *body.agent, options);
    }
    bodies.push_back(std::move(body));
  }
  const double radius = bodies.front().agent->traits().collision_radius;
  if (d.agent_spacing < 2 * radius) {
    throw std::invalid_argument("multi-agent env: agent_spacing=" + std::to_string(d.agent_spacing) +
                                ": below twice the " + d.env.agent + "'s collision radius (" +
                                std::to_string(2 * radius) + " m): robots would spawn inside each other");
  }
  return std::make_unique<MultiBodyEnv>(d, std::move(world), std::move(bodies));
}

}  // namespace bsg::envs
