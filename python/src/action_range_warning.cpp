#include "action_range_warning.h"

#include <string>

namespace py = pybind11;

namespace bsg::python {

void warn_once_if_out_of_range(std::span<const double> actions, const envs::EnvSpec& spec,
                               bool& warned) {
  if (warned) return;
  for (const double value : actions) {
    if (value >= spec.action_low && value <= spec.action_high) continue;
    warned = true;
    const std::string treatment =
        spec.agent == "Car" ? "used as given (the original Car does not clip)"
                            : "clipped to the bounds, as in the original";
    const std::string message = "WARN: " + spec.id + ": an action entry (" +
                                std::string(py::str(py::float_(value))) +
                                ") lies outside the action space [" +
                                std::string(py::str(py::float_(spec.action_low))) + ", " +
                                std::string(py::str(py::float_(spec.action_high))) + "]; it is " +
                                treatment + ". Warned once per environment.";
    if (PyErr_WarnEx(PyExc_UserWarning, message.c_str(), 1) != 0) throw py::error_already_set();
    return;
  }
}

}  // namespace bsg::python
