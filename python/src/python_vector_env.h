// N environments stepped on a C++ thread pool for Python (bsg._core.VectorEnv;
// bsg.VectorEnv adds the spaces). step() copies the actions, releases the GIL
// while the pool steps, and returns batched fresh arrays: observations
// [N, obs_dim], reward, cost [N] float64, terminated, truncated [N] bool, and
// info with one [N] array per cost term, "final_observation" [N, obs_dim]
// (the observations the step produced, before any auto-reset) and
// "_final_observation" [N] bool (which environments ended and were reset).
#pragma once

#include <pybind11/pybind11.h>

#include <array>
#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "envs/vector_env.h"

namespace bsg::python {

class PythonVectorEnv {
 public:
  PythonVectorEnv(pybind11::handle env_id, int num_envs, int num_threads, pybind11::handle seed,
                  const std::string& box_clock, pybind11::handle parameters);

  // seed None: the constructor's seed at the first reset, then each
  // environment's own stream continues; an int: environment i gets seed + i.
  pybind11::tuple reset(pybind11::handle seed, pybind11::handle options);
  pybind11::tuple step(pybind11::handle actions);
  void close();
  bool closed() const { return vector_ == nullptr; }
  const envs::EnvSpec& spec() const { return spec_; }
  int num_envs() const { return num_envs_; }
  int num_threads() const { return num_threads_; }

 private:
  envs::VectorEnv& vector(const char* method);

  std::unique_ptr<envs::VectorEnv> vector_;
  envs::EnvSpec spec_;
  int num_envs_;
  int num_threads_;
  std::uint64_t initial_seed_;
  bool seeded_ = false;
  std::array<pybind11::ssize_t, 2> action_shape_;
  std::vector<double> actions_;  // the pool reads this copy, not Python's array
  std::vector<pybind11::str> cost_term_keys_;
  std::atomic<bool> busy_{false};
};

void bind_vector_env(pybind11::module_& module);

}  // namespace bsg::python
