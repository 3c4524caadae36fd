// Training from Python (bsg.train): `bsg train`'s run in this process, through the same start
// (algos/training/run_start.h) and trainer, so that a run started here is byte for byte the run
// `bsg train` writes from the same configuration (timing columns aside).
//
// The trainer runs with the GIL released. Between epochs it takes the GIL back briefly: to hand
// the epoch's progress row to the callback, and to run Python's signal handlers
// (PyErr_CheckSignals), so that Ctrl-C raises KeyboardInterrupt there. Either an exception from
// the callback or one from a signal handler stops the run as a stop signal stops `bsg train`: at
// the end of the epoch, with a checkpoint, resumable identically; the exception is then raised,
// with the run directory in its notes and in its `bsg_run_dir` attribute. A configuration error
// arrives as ValueError carrying the C++ message.
#pragma once

#include <pybind11/pybind11.h>

namespace bsg::python {

void bind_training(pybind11::module_& module);

}  // namespace bsg::python
