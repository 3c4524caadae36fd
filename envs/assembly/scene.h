// A read-only view of an environment for drawing it (render/, design.md):
// the world whose collision objects are drawn from their shapes, which of them
// are the agent's, and the task's markings without bodies. Building a view
// allocates; it is never on the step path and creates no graphics context.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "envs/env.h"
#include "envs/multi_agent_env.h"
#include "envs/tasks/marking.h"

class btCollisionObject;

namespace bsg::envs {

class World;

struct SceneView {
  const World* world = nullptr;  // its dynamics() lists every collision object
  std::span<const btCollisionObject* const> agent_colliders;
  Vec3 agent_position{};  // base COM
  std::string task;       // "Circle", "Gather", "Reach", "Run"
  double env_dim = 0;     // the world's size parameter (docs/environments.md#worlds)
  std::vector<Marking> markings;
};

// The view of an environment made by make(); throws std::invalid_argument for
// any other Env implementation (it has no world to show).
SceneView scene_view(const Env& env);
// The view of a multi-agent environment made by make_multi_agent: every robot's
// colliders drawn as the agent's, the camera's agent the first robot.
SceneView scene_view(const MultiAgentEnv& env);

}  // namespace bsg::envs
