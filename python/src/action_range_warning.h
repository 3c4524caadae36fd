// Out-of-range actions are not errors: the environments treat them as the
// original suite does (clipped to [-1, 1] by the Ball, the Drone and the Ant,
// used as given by the Car, docs/environments.md "kept quirk 4"). Like
// Gymnasium's passive environment checker, bsg says so once per environment
// with a UserWarning, then stays quiet.
#pragma once

#include <pybind11/pybind11.h>

#include <span>

#include "envs/env.h"

namespace bsg::python {

// Warns (once: sets `warned`) if an entry of `actions` lies outside the
// spec's action bounds. Raises the warning as an exception if Python's
// warning filters turn it into an error.
void warn_once_if_out_of_range(std::span<const double> actions, const envs::EnvSpec& spec,
                               bool& warned);

}  // namespace bsg::python
