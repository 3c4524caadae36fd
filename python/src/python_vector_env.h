// N environments stepped on a C++ thread pool for Python (bsg._core.VectorEnv;
// bsg.VectorEnv adds the spaces and Gymnasium's vector API). step() copies the
// actions, releases the GIL while the pool steps, and returns batched fresh
// arrays: observations [N, obs_dim], reward, cost [N] float64 (the cost only
// in the 6-tuple), terminated, truncated [N] bool, and info as Gymnasium 1.x's
// SyncVectorEnv builds it from the single environments' infos: one [N] array
// per cost term (and "cost" in the 5-tuple) with its "_<key>" mask of the
// environments that reported it, plus, in same-step mode, "final_obs",
// "final_info" and their masks for the environments that ended
// (docs/python.md#vector-environments).
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

  // gymnasium_api: the 5-tuple with info["cost"] instead of the 6-tuple;
  // next_step: Gymnasium's next-step autoreset instead of same-step;
  // max_episode_steps: 0 keeps the environments' own.
  void configure(bool gymnasium_api, bool next_step, int max_episode_steps);

  // seed None: the constructor's seed + i for an environment never reset,
  // else its own stream continues; an int: environment i gets seed + i; a
  // list: one int or None per environment. A seed gives a fresh start (the
  // environment is rebuilt, as PythonEnv). options: None or a dict whose one
  // accepted key is "reset_mask" ([N] bool array: reset only those).
  pybind11::tuple reset(pybind11::handle seed, pybind11::handle options);
  pybind11::tuple step(pybind11::handle actions);
  void close();
  bool closed() const { return vector_ == nullptr; }
  const envs::EnvSpec& spec() const { return spec_; }
  int num_envs() const { return num_envs_; }
  int num_threads() const { return num_threads_; }
  bool next_step() const;
  int max_episode_steps() const;
  // The environments, or RuntimeError if closed (python_render.h).
  envs::VectorEnv& vector(const char* method);
  std::atomic<bool>& busy() { return busy_; }

 private:
  // One [N] float64 column per info key, with its mask, in `info`.
  void add_info_columns(pybind11::dict& info, const std::vector<double>& rows,
                        const std::vector<std::uint8_t>& mask) const;

  std::unique_ptr<envs::VectorEnv> vector_;
  envs::EnvSpec spec_;
  int num_envs_;
  int num_threads_;
  std::uint64_t initial_seed_;
  std::vector<std::uint8_t> ever_reset_;
  bool gymnasium_api_ = false;
  bool warned_out_of_range_ = false;
  std::array<pybind11::ssize_t, 2> action_shape_;
  std::vector<double> actions_;  // the pool reads this copy, not Python's array
  std::vector<pybind11::str> info_keys_;       // cost terms (and "cost"), interned
  std::vector<pybind11::str> info_mask_keys_;  // "_" + each
  std::vector<double> info_rows_;              // N x info_keys_.size()
  std::atomic<bool> busy_{false};
};

void bind_vector_env(pybind11::module_& module);

}  // namespace bsg::python
