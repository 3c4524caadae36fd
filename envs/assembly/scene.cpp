#include "envs/assembly/scene.h"

#include <stdexcept>

#include "envs/assembly/assembled_env.h"
#include "envs/assembly/limb_split_env.h"
#include "envs/assembly/multi_body_env.h"
#include "envs/tasks/layout_checks.h"

namespace bsg::envs {

SceneView scene_view(const Env& env) {
  const auto* assembled = dynamic_cast<const AssembledEnv*>(&env);
  if (assembled == nullptr) {
    throw std::invalid_argument("scene_view: environment '" + env.spec().id +
                                "' was not made by bsg::envs::make and has no world to draw");
  }
  SceneView view;
  view.world = &assembled->world();
  view.agent_colliders = assembled->agent().colliders();
  view.agent_position = to_vec3(assembled->agent().position());
  view.task = env.spec().task;
  view.env_dim = assembled->world().env_dim();
  view.markings = assembled->markings();
  return view;
}

SceneView scene_view(const MultiAgentEnv& env) {
  if (const auto* split = dynamic_cast<const LimbSplitEnv*>(&env)) return scene_view(split->robot());
  const auto* several = dynamic_cast<const MultiBodyEnv*>(&env);
  if (several == nullptr) {
    throw std::invalid_argument("scene_view: environment '" + env.spec().id +
                                "' was not made by bsg::envs::make_multi_agent and has no world to draw");
  }
  SceneView view;
  view.world = &several->world();
  view.agent_colliders = several->robot_colliders();
  view.agent_position = to_vec3(several->agent(0).position());
  view.task = env.spec().task;
  view.env_dim = several->world().env_dim();
  view.markings = several->markings();
  return view;
}

}  // namespace bsg::envs
