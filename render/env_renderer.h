// Renders an environment made by envs::make or envs::make_multi_agent: its scene (envs/assembly/scene.h) from a
// named camera (camera.h) at a fixed size. One renderer per environment; its
// OpenGL context is created here, never by the environment, so an environment
// that is not rendered creates none.
//
// Parameters (RenderOptions):
//   width, height  480 × 360 (the original's rgb_array size), each in [1, 8192]
//   camera         "default" (the task's own camera), "arena", "track" or "top"
#pragma once

#include <string>
#include <vector>

#include "envs/env.h"
#include "envs/multi_agent_env.h"
#include "render/image.h"
#include "render/scene_renderer.h"

namespace bsg::render {

struct RenderOptions {
  int width = 480;
  int height = 360;
  std::string camera = "default";
};

// Throws std::invalid_argument for a size out of [1, 8192] or an unknown
// camera; creates nothing (for callers that create the renderer later).
void require_valid(const RenderOptions& options);

class EnvRenderer {
 public:
  // Throws std::invalid_argument for a bad size or camera name (before any
  // graphics context exists), std::runtime_error naming EGL without a driver.
  explicit EnvRenderer(const RenderOptions& options);

  const RenderOptions& options() const { return options_; }

  // The environment's current state as the camera sees it; with `depth`, each
  // pixel's distance along the view axis in metres.
  void render(const envs::Env& env, Image& image, std::vector<float>* depth = nullptr);
  // The same for a multi-agent environment made by make_multi_agent: every robot drawn.
  void render(const envs::MultiAgentEnv& env, Image& image, std::vector<float>* depth = nullptr);

 private:
  void draw(const envs::SceneView& scene, Image& image, std::vector<float>* depth);

  RenderOptions options_;
  SceneRenderer renderer_;
};

}  // namespace bsg::render
