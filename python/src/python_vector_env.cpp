#include "python_vector_env.h"

#include <pybind11/numpy.h>

#include <stdexcept>

#include "action_input.h"
#include "arguments.h"
#include "exclusive_use.h"
#include "python_env.h"

namespace py = pybind11;

namespace bsg::python {

namespace {

py::array_t<bool> copy_flags(std::span<const std::uint8_t> flags) {
  py::array_t<bool> array(static_cast<py::ssize_t>(flags.size()));
  bool* out = array.mutable_data();
  for (size_t i = 0; i < flags.size(); ++i) out[i] = flags[i] != 0;
  return array;
}

}  // namespace

PythonVectorEnv::PythonVectorEnv(py::handle env_id, int num_envs, int num_threads,
                                 py::handle seed, const std::string& box_clock,
                                 py::handle parameters)
    : initial_seed_(seed_value(seed)) {
  const envs::EnvOptions options = env_options(box_clock);
  const envs::EnvDescription description = env_description(env_id, parameters);
  {
    const py::gil_scoped_release release;  // building N worlds takes a while
    vector_ = std::make_unique<envs::VectorEnv>(description, num_envs, num_threads, options);
  }
  spec_ = vector_->spec();
  num_envs_ = vector_->num_envs();
  num_threads_ = vector_->num_threads();
  action_shape_ = {num_envs_, spec_.action_dim};
}

envs::VectorEnv& PythonVectorEnv::vector(const char* method) {
  if (!vector_) {
    throw std::runtime_error(spec_.id + ": VectorEnv." + method +
                             "() called on a closed environment");
  }
  return *vector_;
}

py::tuple PythonVectorEnv::reset(py::handle seed, py::handle options) {
  if (!options.is_none() && !(py::isinstance<py::dict>(options) && py::len(options) == 0)) {
    throw py::value_error(spec_.id + ": reset() takes no options (got " +
                          std::string(py::repr(options)) + ")");
  }
  const ExclusiveUse use(busy_, spec_.id + " VectorEnv");
  envs::VectorEnv& pool = vector("reset");
  const bool reseed = !seed.is_none() || !seeded_;
  const std::uint64_t value = seed.is_none() ? initial_seed_ : seed_value(seed);
  {
    const py::gil_scoped_release release;
    if (reseed) {
      pool.reset(value);
    } else {
      pool.reset();
    }
  }
  seeded_ = true;
  return py::make_tuple(copy_to_array(pool.observations(), {num_envs_, spec_.observation_dim}),
                        py::dict());
}

py::tuple PythonVectorEnv::step(py::handle actions) {
  const ExclusiveUse use(busy_, spec_.id + " VectorEnv");
  envs::VectorEnv& pool = vector("step");
  const std::span<const double> values = action_values(actions, action_shape_, actions_);
  if (values.data() != actions_.data()) actions_.assign(values.begin(), values.end());
  try {
    const py::gil_scoped_release release;
    pool.step(actions_);
  } catch (const std::invalid_argument& error) {
    raise_invalid_action(error, action_shape_);
  }
  const std::vector<std::string>& names = pool.cost_term_names();
  if (cost_term_keys_.size() != names.size()) {
    cost_term_keys_.assign(names.begin(), names.end());
  }
  py::dict info;
  const std::span<const double> terms = pool.cost_terms();
  for (size_t k = 0; k < names.size(); ++k) {
    py::array_t<double> column(num_envs_);
    double* out = column.mutable_data();
    for (size_t i = 0; i < static_cast<size_t>(num_envs_); ++i) {
      out[i] = terms[i * names.size() + k];
    }
    info[cost_term_keys_[k]] = std::move(column);
  }
  py::array_t<bool> terminated = copy_flags(pool.terminated());
  py::array_t<bool> truncated = copy_flags(pool.truncated());
  py::array_t<bool> ended(num_envs_);
  for (py::ssize_t i = 0; i < num_envs_; ++i) {
    ended.mutable_data()[i] = terminated.data()[i] || truncated.data()[i];
  }
  info["final_observation"] =
      copy_to_array(pool.final_observations(), {num_envs_, spec_.observation_dim});
  info["_final_observation"] = std::move(ended);
  return py::make_tuple(copy_to_array(pool.observations(), {num_envs_, spec_.observation_dim}),
                        copy_to_array(pool.rewards(), {num_envs_}),
                        copy_to_array(pool.costs(), {num_envs_}), std::move(terminated),
                        std::move(truncated), std::move(info));
}

void PythonVectorEnv::close() {
  const ExclusiveUse use(busy_, spec_.id + " VectorEnv");
  const py::gil_scoped_release release;
  vector_.reset();
}

void bind_vector_env(py::module_& module) {
  py::class_<PythonVectorEnv>(module, "VectorEnv", "N environments on a thread pool (see bsg.VectorEnv).")
      .def(py::init<py::handle, int, int, py::handle, const std::string&, py::handle>(),
           py::arg("env_id"), py::arg("num_envs"), py::arg("num_threads") = 0,
           py::arg("seed") = 0, py::arg("box_clock") = "episode_phase",
           py::arg("parameters") = py::none())
      .def("reset", &PythonVectorEnv::reset, py::arg("seed") = py::none(),
           py::arg("options") = py::none())
      .def("step", &PythonVectorEnv::step, py::arg("actions"))
      .def("close", &PythonVectorEnv::close)
      .def_property_readonly("closed", &PythonVectorEnv::closed)
      .def_property_readonly("spec", &PythonVectorEnv::spec)
      .def_property_readonly("num_envs", &PythonVectorEnv::num_envs)
      .def_property_readonly("num_threads", &PythonVectorEnv::num_threads);
}

}  // namespace bsg::python
