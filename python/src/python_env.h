// One environment for Python (bsg._core.Env; bsg.Env adds the spaces):
// reset(seed=None) -> (obs, info) and step(action) -> (obs, reward, cost,
// terminated, truncated, info), Safety-Gymnasium's 6-tuple, where info maps
// every cost term of the task to its value. Observations are fresh float64
// arrays (the C++ buffers are reused at the next step). step() releases the
// GIL while the C++ environment steps.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <array>
#include <atomic>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "envs/env.h"

namespace bsg::python {

class PythonEnv {
 public:
  // Throws ValueError for an unknown id (listing the ids), box_clock or
  // environment parameter (`parameters`: a dict, arguments.h env_description).
  PythonEnv(pybind11::handle env_id, const std::string& box_clock, pybind11::handle parameters);

  // seed None continues the environment's random stream (seed 0 before any
  // seeded reset); options must be None or empty (gymnasium's signature).
  pybind11::tuple reset(pybind11::handle seed, pybind11::handle options);
  pybind11::tuple step(pybind11::handle action);
  // Frees the C++ environment; later reset()/step() raise RuntimeError.
  // Closing twice is allowed.
  void close();
  bool closed() const { return env_ == nullptr; }
  const envs::EnvSpec& spec() const { return spec_; }

  // The environment, or RuntimeError if closed.
  envs::Env& env(const char* method);
  std::atomic<bool>& busy() { return busy_; }

 private:
  std::unique_ptr<envs::Env> env_;
  envs::EnvSpec spec_;
  std::array<pybind11::ssize_t, 1> action_shape_;
  std::vector<double> scratch_;
  std::vector<pybind11::str> cost_term_keys_;  // interned at the first step
  std::atomic<bool> busy_{false};
};

// A fresh float64 array holding `values`, 1-D or with `shape`.
pybind11::array_t<double> copy_to_array(std::span<const double> values);
pybind11::array_t<double> copy_to_array(std::span<const double> values,
                                        std::vector<pybind11::ssize_t> shape);

void bind_env(pybind11::module_& module);

}  // namespace bsg::python
