#include "python_render.h"

#include <pybind11/stl.h>

#include <cstring>
#include <stdexcept>

#include "exclusive_use.h"
#include "render/camera.h"
#include "python_env.h"
#include "python_multi_agent_env.h"
#include "python_vector_env.h"

namespace py = pybind11;

namespace bsg::python {

PythonRenderer::PythonRenderer(int width, int height, const std::string& camera, bool depth)
    : options_{width, height, camera}, depth_(depth) {
  try {
    render::require_valid(options_);
  } catch (const std::invalid_argument& error) {
    throw py::value_error(error.what());
  }
}

std::vector<py::ssize_t> PythonRenderer::frame_shape() const {
  if (depth_) return {options_.height, options_.width};
  return {options_.height, options_.width, 3};
}

template <typename Environment>
void PythonRenderer::render_into(std::unique_ptr<render::EnvRenderer>& renderer,
                                 const Environment& env, void* out) {
  if (!renderer) renderer = std::make_unique<render::EnvRenderer>(options_);
  render::Image image;
  if (depth_) {
    std::vector<float> depth;
    renderer->render(env, image, &depth);
    std::memcpy(out, depth.data(), depth.size() * sizeof(float));
  } else {
    renderer->render(env, image);
    std::memcpy(out, image.rgb.data(), image.rgb.size());
  }
}

template <typename Environment>
py::array PythonRenderer::frame_of(const Environment& env) {
  py::array frame = depth_ ? py::array(py::array_t<float>(frame_shape()))
                           : py::array(py::array_t<std::uint8_t>(frame_shape()));
  void* out = frame.mutable_data();
  {
    const py::gil_scoped_release release;
    render_into(single_, env, out);
  }
  return frame;
}

py::array PythonRenderer::render(PythonEnv& env) {
  const ExclusiveUse use(env.busy(), env.spec().id);
  return frame_of(env.env("render"));
}

py::array PythonRenderer::render_multi_agent(PythonMultiAgentEnv& env) {
  const ExclusiveUse use(env.busy(), env.spec().id);
  return frame_of(env.env("render"));
}

py::array PythonRenderer::render_vector(PythonVectorEnv& vector_env) {
  const ExclusiveUse use(vector_env.busy(), vector_env.spec().id);
  envs::VectorEnv& vector = vector_env.vector("render");
  std::vector<py::ssize_t> shape = frame_shape();
  shape.insert(shape.begin(), vector.num_envs());
  py::array frames = depth_ ? py::array(py::array_t<float>(shape))
                            : py::array(py::array_t<std::uint8_t>(shape));
  auto* out = static_cast<std::uint8_t*>(frames.mutable_data());
  const size_t frame_bytes = static_cast<size_t>(frames.nbytes()) / static_cast<size_t>(vector.num_envs());
  per_env_.resize(static_cast<size_t>(vector.num_envs()));
  {
    const py::gil_scoped_release release;
    vector.for_each_env([&](int i, const envs::Env& env) {
      render_into(per_env_[static_cast<size_t>(i)], env, out + static_cast<size_t>(i) * frame_bytes);
    });
  }
  return frames;
}

void bind_render(py::module_& module) {
  py::class_<PythonRenderer>(module, "Renderer",
                             "Headless OpenGL frames of an Env or VectorEnv (see bsg.make's render_mode).")
      .def(py::init<int, int, const std::string&, bool>(), py::arg("width"), py::arg("height"),
           py::arg("camera"), py::arg("depth"))
      .def("render", &PythonRenderer::render, py::arg("env"))
      .def("render_vector", &PythonRenderer::render_vector, py::arg("vector_env"))
      .def("render_multi_agent", &PythonRenderer::render_multi_agent, py::arg("env"));
  module.attr("camera_names") = render::camera_names();
}

}  // namespace bsg::python
