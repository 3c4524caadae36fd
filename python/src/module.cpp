// The compiled part of the `bsg` Python package (bsg._core): the 16
// environments, one at a time or many on a thread pool. The package's
// __init__.py adds the spaces, make() and the gymnasium wrapper.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "arguments.h"
#include "bench_helpers.h"
#include "envs/env.h"
#include "envs/standard_envs.h"
#include "python_env.h"
#include "python_multi_agent_env.h"
#include "python_multi_agent_vector_env.h"
#include "python_policy.h"
#include "python_render.h"
#include "python_sweep.h"
#include "python_training.h"
#include "python_vector_env.h"

PYBIND11_MODULE(_core, module) {
  module.doc() = "bsg environments (C++ core of the bsg package)";
  // Simulated seconds per environment step (every id): render_fps = 1 / this.
  module.attr("env_step_seconds") = bsg::envs::kStandardEnvStepSeconds;
  module.def("env_ids", &bsg::envs::registered_ids, "Every registered environment id, sorted.");
  module.def(
      "describe",
      [](pybind11::handle env_id, pybind11::handle parameters) {
        return bsg::envs::to_env_overrides(bsg::python::env_description(env_id, parameters));
      },
      pybind11::arg("env_id"), pybind11::arg("parameters") = pybind11::none(),
      "The resolved description as (key, text) pairs, as `bsg envs --describe` prints it.");
  bsg::python::bind_env(module);
  bsg::python::bind_vector_env(module);
  bsg::python::bind_multi_agent_env(module);
  bsg::python::bind_multi_agent_vector_env(module);
  bsg::python::bind_bench_helpers(module);
  bsg::python::bind_render(module);
  bsg::python::bind_policy(module);
  bsg::python::bind_training(module);
  bsg::python::bind_sweep(module);
}
