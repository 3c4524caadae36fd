// Turns what a Python caller passes as an action (a numpy array or a nested
// sequence of numbers) into doubles of an exact shape, or raises ValueError
// naming the expected shape. Integer and floating dtypes are accepted (as
// gymnasium's Box.contains accepts anything safely castable to float64);
// bool, complex, string and object dtypes are not. NaN and infinities are left
// to the C++ environments, which reject them.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <span>
#include <string>
#include <vector>

namespace bsg::python {

// The shape as Python prints it: "(2,)" or "(4, 2)".
std::string shape_text(std::span<const pybind11::ssize_t> shape);

// Doubles of `action`, row-major, checked against `shape`. The span points
// into `action`'s own buffer when it is a C-contiguous float64 array (no copy)
// and into `scratch` otherwise; it is valid while both live.
std::span<const double> action_values(pybind11::handle action,
                                      std::span<const pybind11::ssize_t> shape,
                                      std::vector<double>& scratch);

// Re-raises the C++ environments' std::invalid_argument for a non-finite
// action as ValueError, adding the expected shape.
[[noreturn]] void raise_invalid_action(const std::invalid_argument& error,
                                       std::span<const pybind11::ssize_t> shape);

}  // namespace bsg::python
