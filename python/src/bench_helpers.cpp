#include "bench_helpers.h"

#include <pybind11/numpy.h>

#include <time.h>

#include "envs/env_benchmark.h"
#include "exclusive_use.h"
#include "python_env.h"

namespace py = pybind11;

namespace bsg::python {

namespace {

// CPU seconds of the calling thread: unlike wall time, it does not count the
// time the thread waits for a core on a loaded machine (Python's
// time.thread_time() reads the same clock).
double thread_cpu_seconds() {
  timespec now{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

// Thread CPU seconds the C++ environment takes to step through the rows of
// `actions` (reset, continuing its stream, whenever an episode ends): the
// Python loop doing the same work minus this is the binding's overhead.
double time_cpp_steps(PythonEnv& python_env,
                      const py::array_t<double, py::array::c_style>& actions) {
  const ExclusiveUse use(python_env.busy(), python_env.spec().id);
  envs::Env& env = python_env.env_outside_history("_time_cpp_steps");
  const auto act_dim = static_cast<size_t>(python_env.spec().action_dim);
  if (actions.ndim() != 2 || static_cast<size_t>(actions.shape(1)) != act_dim) {
    throw py::value_error("_time_cpp_steps: actions must have shape (steps, " +
                          std::to_string(act_dim) + ")");
  }
  const std::span<const double> rows(actions.data(), static_cast<size_t>(actions.size()));
  const py::gil_scoped_release release;
  const double start = thread_cpu_seconds();
  for (size_t offset = 0; offset < rows.size(); offset += act_dim) {
    const envs::StepResult result = env.step(rows.subspan(offset, act_dim));
    if (result.terminated || result.truncated) env.reset();
  }
  return thread_cpu_seconds() - start;
}

}  // namespace

void bind_bench_helpers(py::module_& module) {
  module.def("_time_cpp_steps", &time_cpp_steps, py::arg("env"), py::arg("actions"),
             "Benchmark helper: thread CPU seconds the C++ env takes to step through the action rows.");
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
