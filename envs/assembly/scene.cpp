#include "envs/assembly/scene.h"

#include <stdexcept>

#include "envs/assembly/assembled_env.h"
#include "envs/assembly/limb_split_env.h"
#include "envs/assembly/multi_body_env.h"
#include "envs/tasks/layout_checks.h"

namespace bsg::envs {
namespace {

// `followed` is the agent the camera follows; `agent_colliders` are drawn as agents.
SceneView view_of(const World& world, std::span<const btCollisionObject* const> agent_colliders,
                  const Agent& followed, const std::string& task, std::vector<Marking> markings) {
  SceneView view;
  view.world = &world;
  view.agent_colliders = agent_colliders;
  view.agent_position = to_vec3(followed.position());
  view.task = task;
  view.env_dim = world.env_dim();
  view.markings = std::move(markings);
  return view;
}

}  // namespace

SceneView scene_view(const Env& env) {
  const auto* assembled = dynamic_cast<const AssembledEnv*>(&env);
  if (assembled == nullptr) {
    throw std::invalid_argument("scene_view: environment '" + env.spec().id +
                                "' was not made by bsg::envs::make and has no world to draw");
  }
  return view_of(assembled->world(), assembled->agent().colliders(), assembled->agent(), env.spec().task,
                 assembled->markings());
}

SceneView scene_view(const MultiAgentEnv& env) {
  if (const auto* split = dynamic_cast<const LimbSplitEnv*>(&env)) return scene_view(split->robot());
  const auto* several = dynamic_cast<const MultiBodyEnv*>(&env);
  if (several == nullptr) {
    throw std::invalid_argument("scene_view: environment '" + env.spec().id +
                                "' was not made by bsg::envs::make_multi_agent and has no world to draw");
  }
  return view_of(several->world(), several->robot_colliders(), several->agent(0), env.spec().task,
                 several->markings());
}

}  // namespace bsg::envs
