#include "python_env.h"

#include <cstring>
#include <stdexcept>

#include "action_input.h"
#include "arguments.h"
#include "exclusive_use.h"

namespace py = pybind11;

namespace bsg::python {

py::array_t<double> copy_to_array(std::span<const double> values) {
  py::array_t<double> array(static_cast<py::ssize_t>(values.size()));
  std::memcpy(array.mutable_data(), values.data(), values.size_bytes());
  return array;
}

py::array_t<double> copy_to_array(std::span<const double> values,
                                  std::vector<py::ssize_t> shape) {
  py::array_t<double> array(std::move(shape));
  std::memcpy(array.mutable_data(), values.data(), values.size_bytes());
  return array;
}

PythonEnv::PythonEnv(py::handle env_id, const std::string& box_clock, py::handle parameters)
    : env_(envs::make(env_description(env_id, parameters), env_options(box_clock))),
      spec_(env_->spec()),
      action_shape_{spec_.action_dim} {}

envs::Env& PythonEnv::env(const char* method) {
  if (!env_) {
    throw std::runtime_error(spec_.id + ": " + method + "() called on a closed environment");
  }
  return *env_;
}

py::tuple PythonEnv::reset(py::handle seed, py::handle options) {
  if (!options.is_none() && !(py::isinstance<py::dict>(options) && py::len(options) == 0)) {
    throw py::value_error(spec_.id + ": reset() takes no options (got " +
                          std::string(py::repr(options)) + ")");
  }
  const ExclusiveUse use(busy_, spec_.id);
  envs::Env& environment = env("reset");
  std::span<const double> observation;
  if (seed.is_none()) {
    const py::gil_scoped_release release;
    observation = environment.reset();
  } else {
    const std::uint64_t value = seed_value(seed);
    const py::gil_scoped_release release;
    observation = environment.reset(value);
  }
  return py::make_tuple(copy_to_array(observation), py::dict());
}

py::tuple PythonEnv::step(py::handle action) {
  const ExclusiveUse use(busy_, spec_.id);
  envs::Env& environment = env("step");
  const std::span<const double> values = action_values(action, action_shape_, scratch_);
  envs::StepResult result;
  try {
    const py::gil_scoped_release release;
    result = environment.step(values);
  } catch (const std::invalid_argument& error) {
    raise_invalid_action(error, action_shape_);
  }
  if (cost_term_keys_.size() != result.cost_terms.size()) {
    cost_term_keys_.clear();
    for (const envs::CostTerm& term : result.cost_terms) {
      cost_term_keys_.emplace_back(std::string(term.name));
    }
  }
  py::dict info;
  for (size_t k = 0; k < result.cost_terms.size(); ++k) {
    info[cost_term_keys_[k]] = py::float_(result.cost_terms[k].value);
  }
  return py::make_tuple(copy_to_array(result.observation),
                        py::float_(result.reward), py::float_(result.cost),
                        py::bool_(result.terminated), py::bool_(result.truncated),
                        std::move(info));
}

void PythonEnv::close() {
  const ExclusiveUse use(busy_, spec_.id);
  env_.reset();
}

void bind_env(py::module_& module) {
  py::class_<envs::EnvSpec>(module, "EnvSpec",
                            "What a learner needs to know about an environment (read-only).")
      .def_readonly("id", &envs::EnvSpec::id)
      .def_readonly("agent", &envs::EnvSpec::agent)
      .def_readonly("task", &envs::EnvSpec::task)
      .def_readonly("observation_dim", &envs::EnvSpec::observation_dim)
      .def_readonly("action_dim", &envs::EnvSpec::action_dim)
      .def_readonly("max_episode_steps", &envs::EnvSpec::max_episode_steps)
      .def_readonly("cost_limit", &envs::EnvSpec::cost_limit)
      .def_readonly("action_low", &envs::EnvSpec::action_low)
      .def_readonly("action_high", &envs::EnvSpec::action_high)
      .def_readonly("observation_bound", &envs::EnvSpec::observation_bound)
      .def("__repr__", [](const envs::EnvSpec& spec) {
        return "EnvSpec(id='" + spec.id + "', max_episode_steps=" +
               std::to_string(spec.max_episode_steps) +
               ", cost_limit=" + std::string(py::str(py::float_(spec.cost_limit))) + ")";
      });

  py::class_<PythonEnv>(module, "Env", "One environment (see bsg.Env).")
      .def(py::init<py::handle, const std::string&, py::handle>(), py::arg("env_id"),
           py::arg("box_clock") = "episode_phase", py::arg("parameters") = py::none())
      .def("reset", &PythonEnv::reset, py::arg("seed") = py::none(),
           py::arg("options") = py::none(),
           "Resets; returns (observation, info). seed=None continues the random stream.")
      .def("step", &PythonEnv::step, py::arg("action"),
           "Steps; returns (observation, reward, cost, terminated, truncated, info).")
      .def("close", &PythonEnv::close)
      .def_property_readonly("closed", &PythonEnv::closed)
      .def_property_readonly("spec", &PythonEnv::spec);
}

}  // namespace bsg::python
