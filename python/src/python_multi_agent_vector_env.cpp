#include "python_multi_agent_vector_env.h"

#include <pybind11/stl.h>

#include <array>
#include <stdexcept>

#include "action_input.h"
#include "arguments.h"
#include "exclusive_use.h"
#include "python_env.h"

namespace py = pybind11;

namespace bsg::python {

PythonMultiAgentVectorEnv::PythonMultiAgentVectorEnv(const std::string& env_id, int num_envs,
                                                     int num_threads, py::handle seed,
                                                     py::handle parameters)
    : initial_seed_(seed_value(seed)) {
  const envs::MultiAgentDescription description =
      envs::describe_multi_agent(env_id, env_overrides(parameters));
  {
    const py::gil_scoped_release release;  // building N worlds takes a while
    vector_ = std::make_unique<envs::MultiAgentVectorEnv>(description, num_envs, num_threads);
  }
  spec_ = vector_->spec();
  num_envs_ = vector_->num_envs();
  num_threads_ = vector_->num_threads();
  scratch_.resize(static_cast<size_t>(spec_.agent_count()));
}

envs::MultiAgentVectorEnv& PythonMultiAgentVectorEnv::vector(const char* method) const {
  if (!vector_) {
    throw std::runtime_error(spec_.id + ": MultiAgentVectorEnv." + method +
                             "() called on a closed environment");
  }
  return *vector_;
}

template <typename Buffer>
py::list PythonMultiAgentVectorEnv::per_agent(Buffer buffer) const {
  py::list arrays;
  for (int agent = 0; agent < spec_.agent_count(); ++agent) {
    arrays.append(copy_to_array(buffer(agent),
                                {num_envs_, spec_.observation_dims[static_cast<size_t>(agent)]}));
  }
  return arrays;
}

py::list PythonMultiAgentVectorEnv::reset(py::handle seed) {
  const ExclusiveUse use(busy_, spec_.id + " MultiAgentVectorEnv");
  envs::MultiAgentVectorEnv& pool = vector("reset");
  if (seed.is_none()) {
    const py::gil_scoped_release release;
    if (ever_reset_) {
      pool.reset();
    } else {
      pool.reset(initial_seed_);  // new environments: a fresh start
    }
  } else {
    const std::uint64_t value = seed_value(seed);
    const py::gil_scoped_release release;
    pool.restart(value);
  }
  ever_reset_ = true;
  return per_agent([&pool](int agent) { return pool.observations(agent); });
}

py::tuple PythonMultiAgentVectorEnv::step(py::handle actions) {
  const ExclusiveUse use(busy_, spec_.id + " MultiAgentVectorEnv");
  envs::MultiAgentVectorEnv& pool = vector("step");
  const int agents = spec_.agent_count();
  if (!py::isinstance<py::sequence>(actions) || py::isinstance<py::str>(actions) ||
      py::len(actions) != static_cast<size_t>(agents)) {
    throw py::value_error(spec_.id + ": step() needs a sequence of " + std::to_string(agents) +
                          " action arrays [num_envs, act_dim], one per agent in agent order");
  }
  const auto sequence = py::reinterpret_borrow<py::sequence>(actions);
  std::vector<std::span<const double>> values;
  for (int k = 0; k < agents; ++k) {
    const auto agent = static_cast<size_t>(k);
    const std::array<py::ssize_t, 2> shape = {num_envs_, spec_.action_dims[agent]};
    try {
      const std::span<const double> given = action_values(sequence[agent], shape, scratch_[agent]);
      // The pool reads this copy, not Python's array, while the GIL is released.
      if (given.data() != scratch_[agent].data()) scratch_[agent].assign(given.begin(), given.end());
    } catch (const py::value_error& error) {
      throw py::value_error(spec_.id + ": " + spec_.agent_names[agent] + "'s " + error.what());
    }
    values.emplace_back(scratch_[agent]);
  }
  {
    const py::gil_scoped_release release;
    pool.step(values);  // std::invalid_argument (non-finite) becomes ValueError
  }
  const py::ssize_t terms = static_cast<py::ssize_t>(spec_.cost_term_names.size());
  return py::make_tuple(per_agent([&pool](int agent) { return pool.observations(agent); }),
                        copy_to_array(pool.rewards(), {num_envs_, agents}),
                        copy_to_array(pool.costs(), {num_envs_, agents}),
                        copy_flags(pool.terminated()), copy_flags(pool.truncated()),
                        copy_to_array(pool.cost_terms(), {num_envs_, agents, terms}),
                        per_agent([&pool](int agent) { return pool.final_observations(agent); }));
}

py::array_t<double> PythonMultiAgentVectorEnv::state() const {
  return copy_to_array(vector("state").states(), {num_envs_, spec_.state_dim});
}

py::array_t<double> PythonMultiAgentVectorEnv::final_state() const {
  return copy_to_array(vector("final_state").final_states(), {num_envs_, spec_.state_dim});
}

void PythonMultiAgentVectorEnv::close() {
  const ExclusiveUse use(busy_, spec_.id + " MultiAgentVectorEnv");
  const py::gil_scoped_release release;
  vector_.reset();
}

void bind_multi_agent_vector_env(py::module_& module) {
  py::class_<PythonMultiAgentVectorEnv>(module, "MultiAgentVectorEnv",
                                        "N multi-agent environments on a thread pool (see bsg.parallel_vector_env).")
      .def(py::init<const std::string&, int, int, py::handle, py::handle>(), py::arg("env_id"),
           py::arg("num_envs"), py::arg("num_threads") = 0, py::arg("seed") = 0,
           py::arg("parameters") = py::none())
      .def("reset", &PythonMultiAgentVectorEnv::reset, py::arg("seed") = py::none(),
           "Resets; one [num_envs, obs_dim] array per agent. An int seed: environment i gets seed + i.")
      .def("step", &PythonMultiAgentVectorEnv::step, py::arg("actions"),
           "Steps; (observations, rewards, costs, terminated, truncated, cost terms, final observations).")
      .def("state", &PythonMultiAgentVectorEnv::state, "The global states [num_envs, state_dim].")
      .def("final_state", &PythonMultiAgentVectorEnv::final_state,
           "The global states the last step produced, before any auto-reset.")
      .def("close", &PythonMultiAgentVectorEnv::close)
      .def_property_readonly("closed", &PythonMultiAgentVectorEnv::closed)
      .def_property_readonly("spec", &PythonMultiAgentVectorEnv::spec)
      .def_property_readonly("num_envs", &PythonMultiAgentVectorEnv::num_envs)
      .def_property_readonly("num_threads", &PythonMultiAgentVectorEnv::num_threads);
}

}  // namespace bsg::python
