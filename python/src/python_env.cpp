#include "python_env.h"

#include <pybind11/stl.h>

#include <cstring>
#include <stdexcept>

#include "action_input.h"
#include "action_range_warning.h"
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
  if (!values.empty()) {  // memcpy from an empty vector's null data() is undefined
    std::memcpy(array.mutable_data(), values.data(), values.size_bytes());
  }
  return array;
}

py::array_t<bool> copy_flags(std::span<const std::uint8_t> flags) {
  py::array_t<bool> array(static_cast<py::ssize_t>(flags.size()));
  bool* out = array.mutable_data();
  for (size_t i = 0; i < flags.size(); ++i) out[i] = flags[i] != 0;
  return array;
}

PythonEnv::PythonEnv(py::handle env_id, const std::string& box_clock, py::handle parameters)
    : make_env_([description = env_description(env_id, parameters), options = env_options(box_clock)] {
        return envs::make(description, options);
      }),
      env_(make_env_()),
      spec_(env_->spec()),
      max_episode_steps_(spec_.max_episode_steps),
      action_shape_{spec_.action_dim} {}

void PythonEnv::set_max_episode_steps(int steps) {
  if (steps < 0) {
    throw py::value_error(spec_.id + ": max_episode_steps must be >= 1 (or 0: never truncate), " +
                          "got " + std::to_string(steps));
  }
  max_episode_steps_ = steps;
}

envs::Env& PythonEnv::env(const char* method) {
  if (!env_) {
    throw std::runtime_error(spec_.id + ": " + method + "() called on a closed environment");
  }
  return *env_;
}

envs::Env& PythonEnv::env_outside_history(const char* method) {
  envs::Env& environment = env(method);
  history_.lose();
  return environment;
}

py::tuple PythonEnv::reset(py::handle seed, py::handle options) {
  if (!options.is_none() && !(py::isinstance<py::dict>(options) && py::len(options) == 0)) {
    throw py::value_error(spec_.id + ": reset() takes no options (got " +
                          std::string(py::repr(options)) + ")");
  }
  const ExclusiveUse use(busy_, spec_.id);
  env("reset");
  std::span<const double> observation;
  if (seed.is_none()) {
    const py::gil_scoped_release release;
    observation = env_->reset();
    history_.reset();
  } else {
    const std::uint64_t value = seed_value(seed);
    const py::gil_scoped_release release;
    if (used_) env_ = make_env_();  // a fresh start: the episode depends on the seed alone
    observation = env_->reset(value);
    history_.seeded_reset(value);
  }
  used_ = true;
  episode_steps_ = 0;
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
  history_.step(values);
  ++episode_steps_;
  // The environment truncates at spec_.max_episode_steps by the same rule.
  result.truncated =
      !result.terminated && max_episode_steps_ > 0 && episode_steps_ >= max_episode_steps_;
  warn_once_if_out_of_range(values, spec_, warned_out_of_range_);
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

py::tuple PythonEnv::history() const {
  if (!env_) throw std::runtime_error(spec_.id + ": a closed environment cannot be copied");
  if (!history_.complete()) {
    throw std::runtime_error(
        spec_.id + ": cannot copy an environment " + std::to_string(history_.steps()) +
        " steps after its last seeded reset (copies replay at most " +
        std::to_string(EpisodeHistory::kMaxSteps) +
        " steps made through Python); call reset(seed=...) first");
  }
  const auto steps = static_cast<py::ssize_t>(history_.steps());
  return py::make_tuple(
      history_.seed() ? py::object(py::int_(*history_.seed())) : py::object(py::none()),
      py::cast(history_.resets()),
      copy_to_array(history_.actions(), {steps, spec_.action_dim}),
      py::bool_(warned_out_of_range_));
}

void PythonEnv::replay(py::handle history) {
  const ExclusiveUse use(busy_, spec_.id);
  env("replay");
  const auto parts = py::reinterpret_borrow<py::tuple>(history);
  if (used_ || parts.size() != 4) {
    throw py::value_error(spec_.id + ": replay() needs a new environment and a 4-tuple history");
  }
  const auto resets = parts[1].cast<std::vector<std::int64_t>>();
  const auto actions =
      py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(parts[2]);
  if (!actions || actions.ndim() != 2 || actions.shape(1) != spec_.action_dim) {
    throw py::value_error(spec_.id + ": replay() actions must have shape (steps, " +
                          std::to_string(spec_.action_dim) + ")");
  }
  const bool seeded = !parts[0].is_none();
  const std::uint64_t seed = seeded ? seed_value(parts[0]) : 0;
  const std::span<const double> rows(actions.data(), static_cast<size_t>(actions.size()));
  const py::ssize_t steps = actions.shape(0);
  const auto act_dim = static_cast<size_t>(spec_.action_dim);
  const bool warned = parts[3].cast<bool>();
  const py::gil_scoped_release release;
  if (seeded) {
    env_->reset(seed);
    history_.seeded_reset(seed);
    episode_steps_ = 0;
  }
  size_t next_reset = 0;
  for (py::ssize_t t = 0; t <= steps; ++t) {
    while (next_reset < resets.size() && resets[next_reset] == t) {
      env_->reset();
      history_.reset();
      episode_steps_ = 0;
      ++next_reset;
    }
    if (t == steps) break;
    const auto action = rows.subspan(static_cast<size_t>(t) * act_dim, act_dim);
    env_->step(action);
    history_.step(action);
    ++episode_steps_;
  }
  if (next_reset != resets.size()) {
    throw std::invalid_argument(spec_.id + ": replay() resets out of order or beyond the steps");
  }
  used_ = seeded || !resets.empty();
  warned_out_of_range_ = warned;
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
      .def_readonly("cost_term_names", &envs::EnvSpec::cost_term_names,
                    "the task's cost terms, in the order steps report them")
      .def(py::pickle(
          [](const envs::EnvSpec& spec) {  // specs pickle: plain data
            return py::make_tuple(spec.id, spec.agent, spec.task, spec.observation_dim,
                                  spec.action_dim, spec.max_episode_steps, spec.cost_limit,
                                  spec.action_low, spec.action_high, spec.observation_bound,
                                  spec.cost_term_names);
          },
          [](const py::tuple& state) {
            if (state.size() != 11) throw py::value_error("EnvSpec state must have 11 entries");
            return envs::EnvSpec{state[0].cast<std::string>(), state[1].cast<std::string>(),
                                 state[2].cast<std::string>(), state[3].cast<int>(),
                                 state[4].cast<int>(), state[5].cast<int>(),
                                 state[6].cast<double>(), state[7].cast<double>(),
                                 state[8].cast<double>(), state[9].cast<double>(),
                                 state[10].cast<std::vector<std::string>>()};
          }))
      .def("__eq__", [](const envs::EnvSpec& a, const envs::EnvSpec& b) {
        return a.id == b.id && a.agent == b.agent && a.task == b.task &&
               a.observation_dim == b.observation_dim && a.action_dim == b.action_dim &&
               a.max_episode_steps == b.max_episode_steps && a.cost_limit == b.cost_limit &&
               a.action_low == b.action_low && a.action_high == b.action_high &&
               a.observation_bound == b.observation_bound && a.cost_term_names == b.cost_term_names;
      })
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
      .def("_history", &PythonEnv::history,
           "What a copy replays: (seed or None, resets, actions, warned).")
      .def("_replay", &PythonEnv::replay, py::arg("history"),
           "Replays _history() of another environment on this new one.")
      .def_property("_max_episode_steps", &PythonEnv::max_episode_steps,
                    &PythonEnv::set_max_episode_steps)
      .def_property_readonly("closed", &PythonEnv::closed)
      .def_property_readonly("spec", &PythonEnv::spec);
}

}  // namespace bsg::python
