#include "env_builder.h"

#include "assembled_env.h"

#include <stdexcept>

namespace bsg::envs {

std::unique_ptr<Env> build_env(const EnvRegistration& registration, const EnvOptions& options) {
  if (options.physics == PhysicsModel::kLean && !registration.has_lean_model) {
    throw std::invalid_argument(registration.id + ": the " + registration.agent_name +
                                " has no lean physics model (only the Ant and the "
                                "Car have one); use physics: faithful");
  }
  const TaskBlueprint& blueprint = registration.task;
  auto world = std::make_unique<World>(blueprint.layout, blueprint.sub_steps);
  AgentOptions agent_options;
  agent_options.power_upgrade = blueprint.power_upgrade;
  agent_options.physics = options.physics;
  std::unique_ptr<Agent> agent = registration.make_agent(*world, agent_options);
  std::unique_ptr<Task> task = blueprint.make(*world, *agent, options);
  EnvSpec spec;
  spec.id = registration.id;
  spec.agent = registration.agent_name;
  spec.task = blueprint.name;
  spec.max_episode_steps = registration.max_episode_steps;
  spec.cost_limit = registration.cost_limit;
  return std::make_unique<AssembledEnv>(std::move(spec), options, std::move(world),
                                        std::move(agent), std::move(task));
}

}  // namespace bsg::envs
