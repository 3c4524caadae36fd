#include "python_multi_agent_env.h"

#include <pybind11/stl.h>

#include <stdexcept>

#include "action_input.h"
#include "arguments.h"
#include "exclusive_use.h"
#include "python_env.h"

namespace py = pybind11;

namespace bsg::python {

PythonMultiAgentEnv::PythonMultiAgentEnv(const std::string& env_id, py::handle parameters)
    : make_env_([description = envs::describe_multi_agent(env_id, env_overrides(parameters))] {
        return envs::make_multi_agent(description);
      }),
      env_(make_env_()),
      spec_(env_->spec()),
      scratch_(static_cast<size_t>(spec_.agent_count())) {}

const envs::MultiAgentEnv& PythonMultiAgentEnv::env(const char* method) const {
  if (!env_) throw std::runtime_error(spec_.id + ": " + method + "() called on a closed environment");
  return *env_;
}

py::list PythonMultiAgentEnv::observation_list(std::span<const std::span<const double>> observations) const {
  py::list out;
  for (const std::span<const double> observation : observations) out.append(copy_to_array(observation));
  return out;
}

py::list PythonMultiAgentEnv::reset(py::handle seed) {
  const ExclusiveUse use(busy_, spec_.id);
  env("reset");
  std::span<const std::span<const double>> observations;
  if (seed.is_none()) {
    const py::gil_scoped_release release;
    observations = env_->reset();
  } else {
    const std::uint64_t value = seed_value(seed);
    const py::gil_scoped_release release;
    if (used_) env_ = make_env_();  // a fresh start: the episode depends on the seed alone
    observations = env_->reset(value);
  }
  used_ = true;
  return observation_list(observations);
}

py::tuple PythonMultiAgentEnv::step(py::handle actions) {
  const ExclusiveUse use(busy_, spec_.id);
  env("step");
  const auto sequence = py::reinterpret_borrow<py::sequence>(actions);
  if (!py::isinstance<py::sequence>(actions) || py::len(sequence) != static_cast<size_t>(spec_.agent_count())) {
    throw py::value_error(spec_.id + ": step() needs a sequence of " + std::to_string(spec_.agent_count()) +
                          " actions, one per agent in agent order");
  }
  std::vector<std::span<const double>> values;
  for (int k = 0; k < spec_.agent_count(); ++k) {
    const std::array<py::ssize_t, 1> shape = {spec_.action_dims[static_cast<size_t>(k)]};
    values.push_back(action_values(sequence[static_cast<size_t>(k)], shape, scratch_[static_cast<size_t>(k)]));
  }
  envs::MultiAgentStepResult result;
  {
    const py::gil_scoped_release release;
    result = env_->step(values);
  }
  py::list rewards, costs, infos;
  for (int k = 0; k < spec_.agent_count(); ++k) {
    rewards.append(py::float_(result.rewards[static_cast<size_t>(k)]));
    costs.append(py::float_(result.costs[static_cast<size_t>(k)]));
    py::dict terms;
    for (const envs::CostTerm& term : result.cost_terms[static_cast<size_t>(k)]) {
      terms[py::str(std::string(term.name))] = py::float_(term.value);
    }
    infos.append(std::move(terms));
  }
  return py::make_tuple(observation_list(result.observations), std::move(rewards), std::move(costs),
                        py::bool_(result.terminated), py::bool_(result.truncated), std::move(infos));
}

py::array_t<double> PythonMultiAgentEnv::state() const { return copy_to_array(env("state").global_state()); }

void bind_multi_agent_env(py::module_& module) {
  py::class_<envs::MultiAgentSpec>(module, "MultiAgentSpec",
                                   "What a learner needs to know about a multi-agent environment (read-only).")
      .def_readonly("id", &envs::MultiAgentSpec::id)
      .def_readonly("agent", &envs::MultiAgentSpec::agent)
      .def_readonly("task", &envs::MultiAgentSpec::task)
      .def_readonly("partition", &envs::MultiAgentSpec::partition)
      .def_readonly("bodies", &envs::MultiAgentSpec::bodies)
      .def_readonly("agent_names", &envs::MultiAgentSpec::agent_names)
      .def_readonly("observation_dims", &envs::MultiAgentSpec::observation_dims)
      .def_readonly("action_dims", &envs::MultiAgentSpec::action_dims)
      .def_readonly("state_dim", &envs::MultiAgentSpec::state_dim)
      .def_readonly("max_episode_steps", &envs::MultiAgentSpec::max_episode_steps)
      .def_readonly("cost_limit", &envs::MultiAgentSpec::cost_limit)
      .def_readonly("action_low", &envs::MultiAgentSpec::action_low)
      .def_readonly("action_high", &envs::MultiAgentSpec::action_high)
      .def_readonly("observation_bound", &envs::MultiAgentSpec::observation_bound)
      .def_readonly("team_reward", &envs::MultiAgentSpec::team_reward)
      .def_readonly("team_cost", &envs::MultiAgentSpec::team_cost)
      .def_readonly("cost_term_names", &envs::MultiAgentSpec::cost_term_names)
      .def("__repr__", [](const envs::MultiAgentSpec& spec) {
        return "MultiAgentSpec(id='" + spec.id + "', agents=" + std::to_string(spec.agent_count()) + ")";
      });
  py::class_<PythonMultiAgentEnv>(module, "MultiAgentEnv", "One multi-agent environment (see bsg.parallel_env).")
      .def(py::init<const std::string&, py::handle>(), py::arg("env_id"), py::arg("parameters") = py::none())
      .def("reset", &PythonMultiAgentEnv::reset, py::arg("seed") = py::none(),
           "Resets; returns one observation per agent. seed=None continues the random stream.")
      .def("step", &PythonMultiAgentEnv::step, py::arg("actions"),
           "Steps every agent; returns (observations, rewards, costs, terminated, truncated, cost terms).")
      .def("state", &PythonMultiAgentEnv::state, "The global state (centralised critics).")
      .def("close", &PythonMultiAgentEnv::close)
      .def_property_readonly("closed", &PythonMultiAgentEnv::closed)
      .def_property_readonly("spec", &PythonMultiAgentEnv::spec);
  module.def("multi_agent_env_ids", &envs::multi_agent_ids, "Every multi-agent environment id, sorted.");
  module.def(
      "describe_multi_agent",
      [](const std::string& env_id, py::handle parameters) {
        return envs::to_multi_agent_overrides(envs::describe_multi_agent(env_id, env_overrides(parameters)));
      },
      py::arg("env_id"), py::arg("parameters") = py::none(),
      "The resolved multi-agent description as (key, text) pairs.");
}

}  // namespace bsg::python
