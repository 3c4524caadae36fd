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

// An integer in [0, 2**64) (Python's or numpy's); TypeError for anything
// else, ValueError out of range.
std::uint64_t seed_value(pybind11::handle seed);

}  // namespace bsg::python
