#include "arguments.h"

#include <limits>

namespace py = pybind11;

namespace bsg::python {

envs::EnvOptions env_options(const std::string& box_clock) {
  envs::EnvOptions options;
  if (box_clock == "episode_phase") {
    options.box_clock = envs::BoxClock::kEpisodePhase;
  } else if (box_clock == "simulated") {
    options.box_clock = envs::BoxClock::kSimulated;
  } else {
    throw py::value_error("box_clock must be 'episode_phase' or 'simulated', got '" + box_clock +
                          "'");
  }
  return options;
}

envs::EnvOverrides env_overrides(py::handle parameters) {
  envs::EnvOverrides overrides;
  if (parameters.is_none()) return overrides;
  for (const auto& [key, value] : py::cast<py::dict>(parameters)) {
    const std::string name = py::cast<std::string>(key);
    std::string text;
    if (PyBool_Check(value.ptr())) {
      text = value.ptr() == Py_True ? "true" : "false";
    } else if (py::isinstance<py::int_>(value) || py::isinstance<py::float_>(value) ||
               py::isinstance<py::str>(value)) {
      text = py::cast<std::string>(py::str(value));  // repr of a float round-trips
    } else {
      throw py::type_error("environment parameter " + name + " must be a bool, int, float or str, got " +
                           std::string(py::str(value.get_type())));
    }
    overrides.emplace_back(name, text);
  }
  return overrides;
}

envs::EnvDescription env_description(py::handle env_id, py::handle parameters) {
  if (!env_id.is_none() && !py::isinstance<py::str>(env_id)) {
    throw py::type_error("env_id must be a str or None, got " + std::string(py::str(env_id.get_type())));
  }
  const envs::EnvOverrides overrides = env_overrides(parameters);
  const std::string id = env_id.is_none() ? std::string("SafetyBallCircle-v0") : py::cast<std::string>(env_id);
  return envs::describe(id, overrides);
}

std::uint64_t seed_value(py::handle seed) {
  // Any integer (numpy's too, through __index__), but not a bool.
  PyObject* index = PyBool_Check(seed.ptr()) ? nullptr : PyNumber_Index(seed.ptr());
  if (index == nullptr) {
    PyErr_Clear();
    throw py::type_error("seed must be an int or None, got " +
                         std::string(py::str(seed.get_type())));
  }
  const auto value = py::reinterpret_steal<py::int_>(index);
  if (value < py::int_(0) || value > py::int_(std::numeric_limits<std::uint64_t>::max())) {
    throw py::value_error("seed must be in [0, 2**64), got " + std::string(py::str(seed)));
  }
  return value.cast<std::uint64_t>();
}

}  // namespace bsg::python
