// One multi-agent environment for Python (bsg._core.MultiAgentEnv; bsg.parallel_env
// puts PettingZoo's Parallel API around it, python/bsg/parallel.py):
// reset(seed=None) -> [observation per agent] and step([action per agent]) ->
// (observations, rewards, costs, terminated, truncated, cost terms per agent as
// dicts), agent order; state() the global state. Arrays are fresh float64
// copies. As bsg._core.Env, a seeded reset is a fresh start (the environment
// is rebuilt if it was used), and step() releases the GIL.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <atomic>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "envs/multi_agent_env.h"

namespace bsg::python {

class PythonMultiAgentEnv {
 public:
  // ValueError for an unknown id (listing the ids) or a bad parameter.
  PythonMultiAgentEnv(const std::string& env_id, pybind11::handle parameters);

  pybind11::list reset(pybind11::handle seed);
  pybind11::tuple step(pybind11::handle actions);
  pybind11::array_t<double> state() const;
  void close() { env_.reset(); }
  bool closed() const { return env_ == nullptr; }
  const envs::MultiAgentSpec& spec() const { return spec_; }

  // The environment, or RuntimeError if closed.
  const envs::MultiAgentEnv& env(const char* method) const;
  std::atomic<bool>& busy() { return busy_; }

 private:
  pybind11::list observation_list(std::span<const std::span<const double>> observations) const;

  std::function<std::unique_ptr<envs::MultiAgentEnv>()> make_env_;
  std::unique_ptr<envs::MultiAgentEnv> env_;
  envs::MultiAgentSpec spec_;
  bool used_ = false;
  std::vector<std::vector<double>> scratch_;
  std::atomic<bool> busy_{false};
};

void bind_multi_agent_env(pybind11::module_& module);

}  // namespace bsg::python
