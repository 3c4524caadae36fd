// A sweep from Python (bsg.sweep): `bsg sweep GRID`'s local sweep, through the same plan and
// launcher (experiments/sweep_plan.h, experiments/local_launcher.h), whose runs are `bsg train`
// children of the bsg program. The launcher runs with the GIL released and asks for stop signals
// every tenth of a second; each time the GIL is taken back briefly to run Python's signal
// handlers, so that Ctrl-C raises KeyboardInterrupt after the running runs have stopped at the
// end of their epoch with a checkpoint, as `bsg sweep` stops (run it again to resume).
#pragma once

#include <pybind11/pybind11.h>

namespace bsg::python {

void bind_sweep(pybind11::module_& module);

}  // namespace bsg::python
