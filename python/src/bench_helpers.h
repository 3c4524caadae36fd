// Private helpers for python/bench/python_bench.py: the C++ side of the same
// measurement, run inside the module so both sides step identical
// environments with identical actions.
#pragma once

#include <pybind11/pybind11.h>

namespace bsg::python {

void bind_bench_helpers(pybind11::module_& module);

}  // namespace bsg::python
