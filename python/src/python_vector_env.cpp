#include "python_vector_env.h"

#include <pybind11/numpy.h>

#include <optional>
#include <stdexcept>

#include "action_input.h"
#include "action_range_warning.h"
#include "arguments.h"
#include "exclusive_use.h"
#include "python_env.h"

namespace py = pybind11;

namespace bsg::python {

namespace {

bool any_set(const std::vector<std::uint8_t>& flags) {
  for (const std::uint8_t flag : flags) {
    if (flag) return true;
  }
  return false;
}

// options["reset_mask"], checked as Gymnasium's SyncVectorEnv checks it.
std::vector<std::uint8_t> reset_mask(py::handle options, int num_envs, const std::string& id) {
  if (options.is_none()) return {};
  if (!py::isinstance<py::dict>(options)) {
    throw py::type_error(id + ": reset() options must be a dict or None, got " +
                         std::string(py::str(options.get_type())));
  }
  const auto dict = py::reinterpret_borrow<py::dict>(options);
  for (const auto& [key, value] : dict) {
    if (!py::isinstance<py::str>(key) || key.cast<std::string>() != "reset_mask") {
      throw py::value_error(id + ": reset() takes only the option 'reset_mask' (got " +
                            std::string(py::repr(key)) + ")");
    }
  }
  if (!dict.contains("reset_mask")) return {};
  const py::object mask = dict["reset_mask"];
  if (!py::isinstance<py::array>(mask)) {
    throw py::type_error("`options['reset_mask']` must be a numpy array, got " +
                         std::string(py::str(mask.get_type())));
  }
  const auto array = py::reinterpret_borrow<py::array>(mask);
  if (array.ndim() != 1 || array.shape(0) != num_envs) {
    throw py::value_error("`options['reset_mask']` must have shape `(" + std::to_string(num_envs) +
                          ",)`, got " + std::string(py::str(mask.attr("shape"))));
  }
  if (array.dtype().kind() != 'b') {
    throw py::type_error("`options['reset_mask']` must have `dtype=np.bool_`, got " +
                         std::string(py::str(array.dtype())));
  }
  std::vector<std::uint8_t> flags(static_cast<size_t>(num_envs));
  const auto values = py::array_t<bool>::ensure(array);
  for (py::ssize_t i = 0; i < num_envs; ++i) flags[static_cast<size_t>(i)] = values.at(i);
  if (!any_set(flags)) {
    throw py::value_error("`options['reset_mask']` must contain a boolean array with at least "
                          "one True value, got " + std::string(py::str(mask)));
  }
  return flags;
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
  ever_reset_.assign(static_cast<size_t>(num_envs_), 0);
  action_shape_ = {num_envs_, spec_.action_dim};
}

envs::VectorEnv& PythonVectorEnv::vector(const char* method) {
  if (!vector_) {
    throw std::runtime_error(spec_.id + ": VectorEnv." + method +
                             "() called on a closed environment");
  }
  return *vector_;
}

void PythonVectorEnv::configure(bool gymnasium_api, bool next_step, int max_episode_steps) {
  envs::VectorEnv& pool = vector("configure");
  pool.set_max_episode_steps(max_episode_steps);
  pool.set_autoreset(next_step ? envs::AutoReset::kNextStep : envs::AutoReset::kSameStep);
  gymnasium_api_ = gymnasium_api;
}

bool PythonVectorEnv::next_step() const {
  return vector_ && vector_->autoreset() == envs::AutoReset::kNextStep;
}

int PythonVectorEnv::max_episode_steps() const {
  return vector_ ? vector_->max_episode_steps() : spec_.max_episode_steps;
}

py::tuple PythonVectorEnv::reset(py::handle seed, py::handle options) {
  const ExclusiveUse use(busy_, spec_.id + " VectorEnv");
  envs::VectorEnv& pool = vector("reset");
  const std::vector<std::uint8_t> mask = reset_mask(options, num_envs_, spec_.id);
  const auto n = static_cast<size_t>(num_envs_);
  std::vector<std::optional<std::uint64_t>> seeds(n);
  if (seed.is_none()) {
    for (size_t i = 0; i < n; ++i) {
      if (!ever_reset_[i]) seeds[i] = initial_seed_ + i;
    }
  } else if (py::isinstance<py::list>(seed) || py::isinstance<py::tuple>(seed) ||
             (py::isinstance<py::array>(seed) &&
              py::reinterpret_borrow<py::array>(seed).ndim() == 1)) {  // one seed per env
    const auto list = py::reinterpret_borrow<py::sequence>(seed);
    if (py::len(list) != n) {
      throw py::value_error("If seeds are passed as a list the length must match num_envs=" +
                            std::to_string(n) + " but got length=" +
                            std::to_string(py::len(list)) + ".");
    }
    for (size_t i = 0; i < n; ++i) {
      if (!list[i].is_none()) seeds[i] = seed_value(list[i]);
    }
  } else {
    const std::uint64_t first = seed_value(seed);
    for (size_t i = 0; i < n; ++i) seeds[i] = first + i;
  }
  {
    const py::gil_scoped_release release;
    pool.reset_selected(mask, seeds);
  }
  for (size_t i = 0; i < n; ++i) ever_reset_[i] |= mask.empty() || mask[i];
  return py::make_tuple(copy_to_array(pool.observations(), {num_envs_, spec_.observation_dim}),
                        py::dict());
}

void PythonVectorEnv::add_info_columns(py::dict& info, const std::vector<double>& rows,
                                       const std::vector<std::uint8_t>& mask) const {
  const size_t keys = info_keys_.size();
  const auto n = static_cast<size_t>(num_envs_);
  for (size_t k = 0; k < keys; ++k) {
    py::array_t<double> column(num_envs_);
    double* out = column.mutable_data();
    for (size_t i = 0; i < n; ++i) out[i] = mask[i] ? rows[i * keys + k] : 0.0;
    info[info_keys_[k]] = std::move(column);
    info[info_mask_keys_[k]] = copy_flags(mask);
  }
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
  warn_once_if_out_of_range(actions_, spec_, warned_out_of_range_);
  const std::vector<std::string>& names = pool.cost_term_names();
  const size_t keys = names.size() + (gymnasium_api_ ? 1 : 0);
  if (info_keys_.size() != keys) {
    info_keys_.assign(names.begin(), names.end());
    if (gymnasium_api_) info_keys_.emplace_back("cost");
    info_mask_keys_.clear();
    for (const py::str& key : info_keys_) {
      info_mask_keys_.emplace_back("_" + key.cast<std::string>());
    }
  }
  // Each environment's info row: its cost terms, then its cost.
  const auto n = static_cast<size_t>(num_envs_);
  const std::span<const double> terms = pool.cost_terms();
  info_rows_.resize(n * keys);
  for (size_t i = 0; i < n; ++i) {
    for (size_t k = 0; k < names.size(); ++k) {
      info_rows_[i * keys + k] = terms[i * names.size() + k];
    }
    if (gymnasium_api_) info_rows_[i * keys + names.size()] = pool.costs()[i];
  }
  // Which environments report this step's info at the top level: not those
  // reset by this step (next-step mode; their info is the reset's, empty), nor
  // those that ended (same-step mode; their info moves to "final_info").
  std::vector<std::uint8_t> reported(n);
  std::vector<std::uint8_t> ended(n);
  for (size_t i = 0; i < n; ++i) {
    ended[i] = !next_step() && (pool.terminated()[i] || pool.truncated()[i]);
    reported[i] = !pool.autoreset_envs()[i] && !ended[i];
  }
  py::dict info;
  if (any_set(reported)) add_info_columns(info, info_rows_, reported);
  if (any_set(ended)) {
    py::array final_obs(py::dtype("O"), std::vector<py::ssize_t>{num_envs_});  // None-filled
    const auto obs_dim = static_cast<size_t>(spec_.observation_dim);
    for (size_t i = 0; i < n; ++i) {
      py::object row = py::none();
      if (ended[i]) row = copy_to_array(pool.final_observations().subspan(i * obs_dim, obs_dim));
      final_obs.attr("__setitem__")(py::int_(i), row);
    }
    py::dict final_info;
    add_info_columns(final_info, info_rows_, ended);
    info["final_obs"] = std::move(final_obs);
    info["_final_obs"] = copy_flags(ended);
    info["final_info"] = std::move(final_info);
    info["_final_info"] = copy_flags(ended);
  }
  py::array_t<double> observations =
      copy_to_array(pool.observations(), {num_envs_, spec_.observation_dim});
  py::array_t<double> rewards = copy_to_array(pool.rewards(), {num_envs_});
  py::array_t<bool> terminated = copy_flags(pool.terminated());
  py::array_t<bool> truncated = copy_flags(pool.truncated());
  if (gymnasium_api_) {
    return py::make_tuple(std::move(observations), std::move(rewards), std::move(terminated),
                          std::move(truncated), std::move(info));
  }
  return py::make_tuple(std::move(observations), std::move(rewards),
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
      .def("_configure", &PythonVectorEnv::configure, py::arg("gymnasium_api"),
           py::arg("next_step"), py::arg("max_episode_steps"))
      .def("reset", &PythonVectorEnv::reset, py::arg("seed") = py::none(),
           py::arg("options") = py::none())
      .def("step", &PythonVectorEnv::step, py::arg("actions"))
      .def("close", &PythonVectorEnv::close)
      .def_property_readonly("closed", &PythonVectorEnv::closed)
      .def_property_readonly("spec", &PythonVectorEnv::spec)
      .def_property_readonly("num_envs", &PythonVectorEnv::num_envs)
      .def_property_readonly("num_threads", &PythonVectorEnv::num_threads)
      .def_property_readonly("_next_step", &PythonVectorEnv::next_step)
      .def_property_readonly("max_episode_steps", &PythonVectorEnv::max_episode_steps);
}

}  // namespace bsg::python
