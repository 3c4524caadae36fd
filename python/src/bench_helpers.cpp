#include "bench_helpers.h"

#include <pybind11/numpy.h>

#include <chrono>

#include "envs/env_benchmark.h"
#include "exclusive_use.h"
#include "python_env.h"

namespace py = pybind11;

namespace bsg::python {

namespace {

// Seconds the C++ environment takes to step through the rows of `actions`
// (reset, continuing its stream, whenever an episode ends): the Python loop
// doing the same work minus this is the binding's overhead.
double time_cpp_steps(PythonEnv& python_env,
                      const py::array_t<double, py::array::c_style>& actions) {
  const ExclusiveUse use(python_env.busy(), python_env.spec().id);
  envs::Env& env = python_env.env("_time_cpp_steps");
  const auto act_dim = static_cast<size_t>(python_env.spec().action_dim);
  if (actions.ndim() != 2 || static_cast<size_t>(actions.shape(1)) != act_dim) {
    throw py::value_error("_time_cpp_steps: actions must have shape (steps, " +
                          std::to_string(act_dim) + ")");
  }
  const std::span<const double> rows(actions.data(), static_cast<size_t>(actions.size()));
  const py::gil_scoped_release release;
  const auto start = std::chrono::steady_clock::now();
  for (size_t offset = 0; offset < rows.size(); offset += act_dim) {
    const envs::StepResult result = env.step(rows.subspan(offset, act_dim));
    if (result.terminated || result.truncated) env.reset();
  }
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

void bind_bench_helpers(py::module_& module) {
  module.def("_time_cpp_steps", &time_cpp_steps, py::arg("env"), py::arg("actions"),
             "Benchmark helper: seconds the C++ env takes to step through the action rows.");
  module.def(
      "_benchmark_env",
      [](const std::string& id, long steps) {
        envs::EnvBenchmark result;
        {
          const py::gil_scoped_release release;
          result = envs::benchmark_env(id, steps);
        }
        py::dict out;
        out["env_steps_per_second"] = result.env_steps_per_second;
        out["physics_steps_per_second"] = result.physics_steps_per_second;
        return out;
      },
      py::arg("env_id"), py::arg("steps"),
      "Benchmark helper: `bsg bench`'s measurement of one environment.");
}

}  // namespace bsg::python
