// A trained run's policy and its evaluation for Python (bsg.load_policy, bsg.evaluate): the C++
// loader `bsg eval` uses (algos/training/load_policy.h) and its one evaluation
// (algos/training/run_evaluation.h), bound, not rewritten, so that Python's actions and numbers
// are the C++ side's bit for bit.
//
// Policy.act takes one observation [obs_dim] or a batch [N, obs_dim] and returns float64 actions
// [act_dim] or [N, act_dim], each row acted on as `bsg eval` acts on it (the GIL released).
// Sampled actions (deterministic=False) draw from the policy's own stream, which starts where a
// one-process `bsg eval --actions sampled` starts (derive_seed(run seed, evaluation_action_noise,
// rank 0)).
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <memory>
#include <string>

#include "algos/training/load_policy.h"
#include "common/random.h"
#include "envs/env.h"

namespace bsg::python {

class PythonPolicy {
 public:
  // RuntimeError naming the directory or file at fault (not a run directory, corrupt checkpoint).
  explicit PythonPolicy(const std::string& run_dir);

  pybind11::array_t<double> act(pybind11::handle observation, bool deterministic);
  const algos::LoadedPolicy& policy() const { return *policy_; }
  const std::string& run_dir() const { return run_dir_; }
  // The spec of the run's environment (its env: block and physics applied).
  const envs::EnvSpec& env_spec() const { return env_spec_; }

 private:
  std::string run_dir_;
  std::unique_ptr<algos::LoadedPolicy> policy_;
  envs::EnvSpec env_spec_;
  Rng noise_;
};

void bind_policy(pybind11::module_& module);

}  // namespace bsg::python
