// One environment for Python (bsg._core.Env; bsg.Env adds the spaces):
// reset(seed=None) -> (obs, info) and step(action) -> (obs, reward, cost,
// terminated, truncated, info), Safety-Gymnasium's 6-tuple, where info maps
// every cost term of the task to its value. Observations are fresh float64
// arrays (the C++ buffers are reused at the next step). step() releases the
// GIL while the C++ environment steps.
//
// A seeded reset is a fresh start: an environment that was used is rebuilt
// first, so that reset(seed=s) plays the same episode whatever came before
// (the C++ Env::reset(seed) keeps the original's history-dependent reset,
// which training's per-epoch reseeding relies on; docs/python.md#seeds).
// reset() without a seed continues as the C++ Env::reset() does.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <array>
#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "envs/env.h"
#include "episode_history.h"

namespace bsg::python {

class PythonEnv {
 public:
  // Throws ValueError for an unknown id (listing the ids), box_clock or
  // environment parameter (`parameters`: a dict, arguments.h env_description).
  PythonEnv(pybind11::handle env_id, const std::string& box_clock, pybind11::handle parameters);

  // seed None continues the environment's random stream (seed 0 before any
  // seeded reset); options must be None or empty (gymnasium's signature).
  pybind11::tuple reset(pybind11::handle seed, pybind11::handle options);
  // (seed or None, resets, actions [steps, action_dim], warned): see
  // EpisodeHistory; RuntimeError if closed or the history is too long.
  pybind11::tuple history() const;
  // Replays history() of an environment of the same id and options on this
  // new one (ValueError if it was used or the history does not fit).
  void replay(pybind11::handle history);
  pybind11::tuple step(pybind11::handle action);
  // Frees the C++ environment; later reset()/step() raise RuntimeError.
  // Closing twice is allowed.
  void close();
  bool closed() const { return env_ == nullptr; }
  // Truncation after this many steps of an episode (0: never, when a wrapper
  // such as gymnasium's TimeLimit truncates instead); spec's by default.
  int max_episode_steps() const { return max_episode_steps_; }
  void set_max_episode_steps(int steps);
  const envs::EnvSpec& spec() const { return spec_; }

  // The environment, or RuntimeError if closed.
  envs::Env& env(const char* method);
  // The same, for stepping it from C++ (benchmarks): copies are refused afterwards
  // until the next seeded reset, as they could not replay those steps.
  envs::Env& env_outside_history(const char* method);
  std::atomic<bool>& busy() { return busy_; }

 private:
  std::function<std::unique_ptr<envs::Env>()> make_env_;
  std::unique_ptr<envs::Env> env_;
  bool used_ = false;  // reset or stepped since built
  EpisodeHistory history_;
  bool warned_out_of_range_ = false;
  envs::EnvSpec spec_;
  int max_episode_steps_;
  int episode_steps_ = 0;
  std::array<pybind11::ssize_t, 1> action_shape_;
  std::vector<double> scratch_;
  std::vector<pybind11::str> cost_term_keys_;  // interned at the first step
  std::atomic<bool> busy_{false};
};

// A fresh float64 array holding `values`, 1-D or with `shape`.
pybind11::array_t<double> copy_to_array(std::span<const double> values);
pybind11::array_t<double> copy_to_array(std::span<const double> values,
                                        std::vector<pybind11::ssize_t> shape);
// A fresh bool array, true where `flags` is non-zero.
pybind11::array_t<bool> copy_flags(std::span<const std::uint8_t> flags);

void bind_env(pybind11::module_& module);

}  // namespace bsg::python
