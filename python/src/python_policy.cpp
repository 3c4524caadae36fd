#include "python_policy.h"

#include <pybind11/stl.h>

#include <optional>
#include <stdexcept>
#include <vector>

#include "action_input.h"
#include "algos/training/evaluation_files.h"
#include "algos/training/run_environment.h"
#include "algos/training/run_evaluation.h"
#include "common/mpi_context.h"
#include "common/run_config_schema.h"
#include "common/seeding.h"
#include "render/episode_recorders.h"

namespace py = pybind11;

namespace bsg::python {
namespace {

std::uint64_t sampled_action_seed(const RunConfig& config) {
  return derive_seed(static_cast<std::uint64_t>(config.seed), SeedStream::evaluation_action_noise, 0);
}

std::unique_ptr<algos::LoadedPolicy> load(const std::string& run_dir) {
  try {
    return algos::load_policy(algos::RunDirectory(run_dir));
  } catch (const std::exception& e) {
    // Every way a directory can fail to hold a run (missing files, a config or checkpoint that
    // does not read) arrives as one RuntimeError with the loader's message.
    throw std::runtime_error(std::string("bsg.load_policy: ") + e.what());
  }
}

py::array_t<double> to_array(const Eigen::VectorXd& values) {
  py::array_t<double> array(values.size());
  for (Eigen::Index i = 0; i < values.size(); ++i) array.mutable_at(i) = values(i);
  return array;
}

py::object standardization(const algos::LoadedPolicy& policy) {
  const std::optional<algos::ObservationStandardization> s = policy.observation_standardization();
  if (!s) return py::none();
  py::dict out;
  out["mean"] = to_array(s->mean);
  out["std"] = to_array(s->std);
  out["std_epsilon"] = s->std_epsilon;
  out["clip"] = s->clip > 0.0 ? py::object(py::float_(s->clip)) : py::object(py::none());
  return out;
}

// The resolved configuration as key -> YAML text (config.yaml's values).
py::dict config_dict(const RunConfig& config) {
  py::dict out;
  for (const ConfigKey& key : run_config_schema()) {
    out[py::str(std::string(key.key))] = config_value_to_yaml(config, key);
  }
  return out;
}

struct EvaluationRequest {
  std::string run_dir;
  std::optional<int> episodes;
  std::optional<std::int64_t> seed;
  std::optional<std::string> actions;  // "mean" or "sampled"
  std::optional<std::string> video;    // MP4 path
  render::RenderOptions render;
};

// (evaluation JSON as `bsg eval --json` prints it, epochs of the checkpoint, epochs of the run,
// frames of the video or 0).
py::tuple evaluate(const EvaluationRequest& request) {
  std::optional<algos::EvaluationActions> actions;
  if (request.actions) {
    if (*request.actions != "mean" && *request.actions != "sampled") {
      throw py::value_error("bsg.evaluate: actions must be 'mean' or 'sampled', got '" + *request.actions + "'");
    }
    actions = *request.actions == "sampled" ? algos::EvaluationActions::sampled : algos::EvaluationActions::mean;
  }
  if (request.episodes && *request.episodes < 0) {
    throw py::value_error("bsg.evaluate: episodes must be >= 0, got " + std::to_string(*request.episodes));
  }
  algos::RunEvaluation result;
  int frames = 0;
  {
    const py::gil_scoped_release release;
    try {
      // The video is opened before any episode runs: a bad path, size or camera fails first.
      std::unique_ptr<render::VideoRecorder> video;
      if (request.video) video = std::make_unique<render::VideoRecorder>(*request.video, request.render);
      result = algos::evaluate_run_directory(
          algos::RunDirectory(request.run_dir), request.episodes, MpiContext::single_process(),
          [&](std::unique_ptr<envs::Env> env) -> std::unique_ptr<envs::Env> {
            if (!video) return env;
            return std::make_unique<render::ObservedEnv>(std::move(env), *video);
          },
          actions, request.seed);
      if (video) frames = video->close();
    } catch (const std::exception& e) {
      throw std::runtime_error(std::string("bsg.evaluate: ") + e.what());
    }
  }
  return py::make_tuple(algos::evaluation_json(result.summary, true), result.epochs_completed, result.epochs, frames);
}

}  // namespace

PythonPolicy::PythonPolicy(const std::string& run_dir)
    : run_dir_(run_dir),
      policy_(load(run_dir)),
      env_spec_(algos::make_run_env(policy_->config())->spec()),
      noise_(sampled_action_seed(policy_->config())) {}

py::array_t<double> PythonPolicy::act(py::handle observation, bool deterministic) {
  const py::ssize_t observation_size = policy_->observation_size();
  const py::ssize_t action_size = policy_->action_size();
  const py::array given = py::array::ensure(observation);
  if (!given) throw py::value_error("act: the observation must be an array of numbers");
  const bool batch = given.ndim() == 2;
  if (given.ndim() != 1 && !batch) {
    throw py::value_error("act: expected an observation of shape (" + std::to_string(observation_size) +
                          ",) or a batch of shape (N, " + std::to_string(observation_size) + "), got " +
                          shape_text(std::span<const py::ssize_t>(given.shape(), given.ndim())));
  }
  const py::ssize_t rows = batch ? given.shape(0) : 1;
  const std::vector<py::ssize_t> shape = batch ? std::vector<py::ssize_t>{rows, observation_size}
                                               : std::vector<py::ssize_t>{observation_size};
  std::vector<double> scratch;
  const std::span<const double> values = action_values(observation, shape, scratch);
  py::array_t<double> actions(batch ? std::vector<py::ssize_t>{rows, action_size}
                                    : std::vector<py::ssize_t>{action_size});
  double* out = actions.mutable_data();
  const algos::ActionMode mode = deterministic ? algos::ActionMode::mean : algos::ActionMode::sampled;
  {
    const py::gil_scoped_release release;
    const auto obs = static_cast<std::size_t>(observation_size);
    const auto act = static_cast<std::size_t>(action_size);
    for (std::size_t r = 0; r < static_cast<std::size_t>(rows); ++r) {
      policy_->act(values.subspan(r * obs, obs), mode, noise_, std::span<double>(out + r * act, act));
    }
  }
  return actions;
}

void bind_policy(py::module_& module) {
  py::class_<PythonPolicy>(module, "Policy")
      .def(py::init<const std::string&>(), py::arg("run_dir"))
      .def("act", &PythonPolicy::act, py::arg("observation"), py::arg("deterministic") = true)
      .def_property_readonly("run_dir", &PythonPolicy::run_dir)
      .def_property_readonly("env_spec", &PythonPolicy::env_spec, py::return_value_policy::reference_internal)
      .def_property_readonly("env_id", [](const PythonPolicy& p) { return p.policy().config().env_id; })
      .def_property_readonly("alg", [](const PythonPolicy& p) { return std::string(to_string(p.policy().config().alg)); })
      .def_property_readonly("epochs_completed", [](const PythonPolicy& p) { return p.policy().epochs_completed(); })
      .def_property_readonly("epochs", [](const PythonPolicy& p) { return p.policy().config().epochs; })
      .def_property_readonly("observation_size", [](const PythonPolicy& p) { return p.policy().observation_size(); })
      .def_property_readonly("action_size", [](const PythonPolicy& p) { return p.policy().action_size(); })
      .def_property_readonly("sampled_action_std", [](const PythonPolicy& p) { return p.policy().sampled_action_std(); })
      .def_property_readonly("observation_standardization",
                             [](const PythonPolicy& p) { return standardization(p.policy()); })
      .def_property_readonly("config", [](const PythonPolicy& p) { return config_dict(p.policy().config()); });
  module.def(
      "evaluate",
      [](const std::string& run_dir, std::optional<int> episodes, std::optional<std::int64_t> seed,
         std::optional<std::string> actions, std::optional<std::string> video, const std::string& camera, int width,
         int height) {
        EvaluationRequest request{run_dir, episodes, seed, actions, video, {}};
        request.render.camera = camera;
        request.render.width = width;
        request.render.height = height;
        return evaluate(request);
      },
      py::arg("run_dir"), py::arg("episodes"), py::arg("seed"), py::arg("actions"), py::arg("video"),
      py::arg("camera"), py::arg("width"), py::arg("height"));
}

}  // namespace bsg::python
