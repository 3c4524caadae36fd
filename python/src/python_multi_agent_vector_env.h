// N copies of one multi-agent environment on the C++ thread pool for Python
// (bsg._core.MultiAgentVectorEnv; bsg.parallel_vector_env puts agent names
// and spaces around it, python/bsg/parallel_vector.py). Lists are in agent
// order, arrays fresh float64 (flags bool) copies:
//   reset(seed=None) -> [observations [N, obs_dim] per agent]
//   step([actions [N, act_dim] per agent]) -> (observations per agent,
//       rewards [N, agents], costs [N, agents], terminated [N], truncated [N],
//       cost terms [N, agents, terms], final observations per agent)
//   state(), final_state() -> [N, state_dim]
// A seeded reset is a fresh start (environment i plays what a new
// bsg.parallel_env reset with seed + i plays); reset() without a seed starts
// from the constructor's seed the first time and continues every
// environment's stream after. step() releases the GIL while the pool steps.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "envs/multi_agent_vector_env.h"

namespace bsg::python {

class PythonMultiAgentVectorEnv {
 public:
  // ValueError for an unknown id (listing the ids), a bad parameter,
  // num_envs < 1 or num_threads < 0.
  PythonMultiAgentVectorEnv(const std::string& env_id, int num_envs, int num_threads,
                            pybind11::handle seed, pybind11::handle parameters);

  pybind11::list reset(pybind11::handle seed);
  pybind11::tuple step(pybind11::handle actions);
  pybind11::array_t<double> state() const;
  pybind11::array_t<double> final_state() const;
  void close();
  bool closed() const { return vector_ == nullptr; }
  const envs::MultiAgentSpec& spec() const { return spec_; }
  int num_envs() const { return num_envs_; }
  int num_threads() const { return num_threads_; }

 private:
  // The environments, or RuntimeError if closed.
  envs::MultiAgentVectorEnv& vector(const char* method) const;
  // One [N, observation_dims[agent]] array per agent from `buffer(agent)`.
  template <typename Buffer>
  pybind11::list per_agent(Buffer buffer) const;

  std::unique_ptr<envs::MultiAgentVectorEnv> vector_;
  envs::MultiAgentSpec spec_;
  int num_envs_;
  int num_threads_;
  std::uint64_t initial_seed_;
  bool ever_reset_ = false;
  std::vector<std::vector<double>> scratch_;  // per agent: actions that needed a conversion
  std::atomic<bool> busy_{false};
};

void bind_multi_agent_vector_env(pybind11::module_& module);

}  // namespace bsg::python
