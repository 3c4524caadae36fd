// Python arguments shared by Env and VectorEnv: environment options by name and
// seeds, each checked with an error naming the bad value.
#pragma once

#include <pybind11/pybind11.h>

#include <cstdint>
#include <string>

#include "envs/env.h"

namespace bsg::python {

// box_clock: "episode_phase" (default) or "simulated" (env.h EnvOptions).
envs::EnvOptions env_options(const std::string& box_clock);

// The keyword arguments in `parameters` (a dict, or None) as (key, text)
// pairs: bools as true/false, ints and floats as Python writes them, strings as
// they are; TypeError for another value type.
envs::EnvOverrides env_overrides(pybind11::handle parameters);

// The description of `env_id` with the keyword arguments in `parameters` (a
// dict of environment parameters, envs/description/env_parameters.h) applied: bools as
// true/false, ints and floats as Python writes them, strings as they are.
// env_id None starts from SafetyBallCircle-v0 (give agent= and task=).
// TypeError for another value type; ValueError (one line naming the key and
// value) for a bad key or value.
envs::EnvDescription env_description(pybind11::handle env_id, pybind11::handle parameters);

// An integer in [0, 2**64) (Python's or numpy's); TypeError for anything
// else, ValueError out of range.
std::uint64_t seed_value(pybind11::handle seed);

}  // namespace bsg::python
