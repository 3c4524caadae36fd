#include "python_training.h"

#include <pybind11/iostream.h>
#include <pybind11/stl.h>

#include <filesystem>
#include <optional>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "algos/training/run_directory.h"
#include "algos/training/run_start.h"
#include "common/config_error.h"
#include "common/mpi_context.h"
#include "common/run_config_resolve.h"
#include "config_values.h"
#include "configs_lookup.h"

namespace py = pybind11;

namespace bsg::python {
namespace {

struct TrainingRequest {
  std::optional<std::string> config_file;  // a run file, or
  py::object config_dict;                  // a dict in its place (None: neither)
  py::dict overrides;                      // keywords, as --set
  std::optional<std::string> out;
  std::optional<std::string> configs;
  std::optional<std::string> resume;
  py::object callback;  // None or callable(row: dict)
  bool verbose = true;
  int stop_after_epochs = 0;
  std::string package_dir;
};

RunConfig resolve_config(const TrainingRequest& request) {
  const std::filesystem::path run_file = request.config_file.value_or("");
  if (!run_file.empty() && !std::filesystem::is_regular_file(run_file)) {
    throw ConfigError("run file " + run_file.string() + " does not exist");
  }
  RunConfigRequest resolve;
  resolve.configs_dir = find_configs(request.configs.value_or(""), run_file, "run file", request.package_dir).dir;
  resolve.run_file = run_file;
  if (!request.config_dict.is_none()) {
    resolve.run_entries = config_entries_from_dict(request.config_dict, "config",
                                                   [](const std::string& key) { return "config['" + key + "']"; });
    resolve.run_entries_name = "config dict";
  }
  resolve.set_entries = config_entries_from_dict(request.overrides, "the keyword arguments", [](const std::string& key) {
    return "bsg.train(" + key + "=...)";
  });
  return algos::resolve_training_config(std::move(resolve));
}

py::dict row_dict(const std::vector<algos::NamedScalar>& row) {
  py::dict out;
  for (const algos::NamedScalar& column : row) out[py::str(column.name)] = column.value;
  return out;
}

// Tells the exception's reader where the run is and, if it stopped early, how to continue it.
void note_stopped_run(const py::error_already_set& error, const std::string& run_dir,
                      const algos::TrainingOutcome& outcome, int epochs) {
  const py::object exception = error.value();
  const std::string note =
      outcome.finished ? "bsg.train: the run in " + run_dir + " finished all " + std::to_string(epochs) + " epochs"
                       : "bsg.train: stopped after " + std::to_string(outcome.epochs_completed) + " of " +
                             std::to_string(epochs) + " epochs with a checkpoint; continue with bsg.train(resume='" +
                             run_dir + "') or bsg train --resume " + run_dir;
  try {
    py::setattr(exception, "bsg_run_dir", py::str(run_dir));
    if (py::hasattr(exception, "add_note")) exception.attr("add_note")(note);
  } catch (const py::error_already_set&) {
    // An exception type that takes no attributes keeps its own message only.
  }
}

// (run directory, epochs completed, finished).
py::tuple train(const TrainingRequest& request) {
  RunConfig config;
  std::optional<algos::RunDirectory> directory;
  const MpiContext mpi = MpiContext::single_process();
  try {
    if (request.resume) {
      if (request.config_file || !request.config_dict.is_none() || !request.overrides.empty()) {
        throw ConfigError("resume takes the configuration from the run directory; give no config or keywords");
      }
      directory.emplace(*request.resume);
      config = algos::resumed_training_config(*directory);
    } else {
      config = resolve_config(request);
      directory.emplace(request.out ? std::filesystem::path(*request.out) : algos::default_run_directory(config));
    }
    algos::check_before_training(config, mpi.size());
  } catch (const ConfigError& e) {
    throw py::value_error(e.what());
  }

  // Progress lines go to Python's sys.stdout (a notebook shows them), written with the GIL taken.
  std::ostream log(nullptr);
  std::optional<py::scoped_ostream_redirect> redirect;
  if (request.verbose) redirect.emplace(log, py::module_::import("sys").attr("stdout"));

  std::optional<py::error_already_set> pending;  // the exception that stops the run
  algos::TrainerOptions options;
  options.resume = request.resume.has_value();
  options.stop_after_epochs = request.stop_after_epochs;
  options.log = request.verbose ? &log : nullptr;
  if (!request.callback.is_none()) {
    options.on_progress_row = [&](int, const std::vector<algos::NamedScalar>& row) {
      const py::gil_scoped_acquire acquire;
      if (pending) return;
      try {
        request.callback(row_dict(row));
      } catch (py::error_already_set& error) {
        pending.emplace(std::move(error));
      }
    };
  }
  options.stop_requested = [&] {
    const py::gil_scoped_acquire acquire;
    if (!pending && PyErr_CheckSignals() != 0) pending.emplace();
    return pending.has_value();
  };

  algos::TrainingOutcome outcome;
  {
    const py::gil_scoped_release release;
    try {
      outcome = algos::allocate_trainer(config, *directory, mpi, options)->run();
    } catch (const ConfigError& e) {
      throw py::value_error(e.what());
    }
  }
  redirect.reset();
  if (pending) {
    note_stopped_run(*pending, directory->root.string(), outcome, config.epochs);
    throw *pending;
  }
  return py::make_tuple(directory->root.string(), outcome.epochs_completed, outcome.finished);
}

}  // namespace

void bind_training(py::module_& module) {
  module.def(
      "train",
      [](std::optional<std::string> config_file, py::object config_dict, py::dict overrides,
         std::optional<std::string> out, std::optional<std::string> configs, std::optional<std::string> resume,
         py::object callback, bool verbose, int stop_after_epochs, std::string package_dir) {
        if (stop_after_epochs < 0) {
          throw py::value_error("stop_after must be >= 0, got " + std::to_string(stop_after_epochs));
        }
        return train(TrainingRequest{std::move(config_file), std::move(config_dict), std::move(overrides),
                                     std::move(out), std::move(configs), std::move(resume), std::move(callback),
                                     verbose, stop_after_epochs, std::move(package_dir)});
      },
      py::arg("config_file"), py::arg("config_dict"), py::arg("overrides"), py::arg("out"), py::arg("configs"),
      py::arg("resume"), py::arg("callback"), py::arg("verbose"), py::arg("stop_after"), py::arg("package_dir"));
}

}  // namespace bsg::python
