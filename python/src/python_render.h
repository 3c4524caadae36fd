// Rendering for Python (bsg._core.Renderer; bsg.make(render_mode=...) uses
// it): an Env's frame as an [H, W, 3] uint8 array, or its depth as [H, W]
// float32 metres; a VectorEnv's frames as [N, H, W, 3] (or [N, H, W]),
// rendered on the pool's threads with the GIL released. The size and camera
// are checked at construction; the OpenGL context is created at the first
// render, so an environment made with a render mode that never renders
// creates none.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <memory>
#include <vector>

#include "render/env_renderer.h"

namespace bsg::python {

class PythonEnv;
class PythonMultiAgentEnv;
class PythonVectorEnv;

class PythonRenderer {
 public:
  // ValueError for a bad size or camera.
  PythonRenderer(int width, int height, const std::string& camera, bool depth);

  pybind11::array render(PythonEnv& env);
  pybind11::array render_vector(PythonVectorEnv& vector_env);
  pybind11::array render_multi_agent(PythonMultiAgentEnv& env);

 private:
  std::vector<pybind11::ssize_t> frame_shape() const;
  // Renders `env` with `renderer` (created here on first use) into `out`.
  // One frame of `env` with the single renderer. These two templates take an
  // envs::Env or an envs::MultiAgentEnv and are instantiated in the source file.
  template <typename Environment>
  pybind11::array frame_of(const Environment& env);
  template <typename Environment>
  void render_into(std::unique_ptr<render::EnvRenderer>& renderer, const Environment& env, void* out);

  render::RenderOptions options_;
  bool depth_;
  std::unique_ptr<render::EnvRenderer> single_;
  std::vector<std::unique_ptr<render::EnvRenderer>> per_env_;  // one per vector environment
};

void bind_render(pybind11::module_& module);

}  // namespace bsg::python
