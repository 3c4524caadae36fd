#include "python_sweep.h"

#include <pybind11/stl.h>

#include <algorithm>
#include <csignal>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "common/config_error.h"
#include "configs_lookup.h"
#include "experiments/local_launcher.h"
#include "experiments/run_lock.h"
#include "experiments/sweep_plan.h"

namespace py = pybind11;

namespace bsg::python {
namespace {

struct SweepRequest {
  std::string grid_file;
  std::optional<std::string> out;
  std::optional<std::string> configs;
  int jobs = 0;  // 0: cores / ranks_per_run
  int ranks_per_run = 1;
  std::vector<std::string> only_env_ids;
  std::vector<std::string> only_algorithms;
  std::string program;  // the bsg program the runs are children of
  std::string package_dir;
};

experiments::SweepPlanRequest plan_request(const SweepRequest& request) {
  const std::filesystem::path grid_file(request.grid_file);
  experiments::SweepPlanRequest plan;
  plan.grid_file = grid_file;
  plan.configs_dir = find_configs(request.configs.value_or(""), grid_file, "grid file", request.package_dir).dir;
  plan.out_dir = request.out ? std::filesystem::path(*request.out) : std::filesystem::path("sweeps") / grid_file.stem();
  plan.only_env_ids = request.only_env_ids;
  plan.only_algorithms = request.only_algorithms;
  plan.ranks_per_run = request.ranks_per_run;
  return plan;
}

// The sweep directory; ValueError for a bad grid, RuntimeError if a run failed.
std::string sweep(const SweepRequest& request) {
  if (request.ranks_per_run < 1) throw py::value_error("ranks_per_run must be >= 1");
  if (request.jobs < 0) throw py::value_error("jobs must be >= 1 (or 0: cores / ranks_per_run)");
  experiments::LocalLaunchOptions launch;
  launch.ranks_per_run = request.ranks_per_run;
  launch.bsg_program = request.program;
  launch.jobs = request.jobs;
  if (launch.jobs == 0) {
    const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
    launch.jobs = static_cast<int>(std::max(1u, cores / static_cast<unsigned>(request.ranks_per_run)));
  }
  std::optional<py::error_already_set> pending;  // the exception that stops the sweep
  launch.take_stop_signal = [&pending] {
    const py::gil_scoped_acquire acquire;
    if (PyErr_CheckSignals() == 0) return 0;
    if (!pending) pending.emplace();
    PyErr_Clear();  // a second Ctrl-C only repeats the request
    return SIGINT;
  };
  experiments::SweepPlanRequest plan_inputs;
  int status = 0;
  {
    const py::gil_scoped_release release;
    try {
      plan_inputs = plan_request(request);
      launch.configs_dir = plan_inputs.configs_dir;
      const experiments::RunLock lock = experiments::lock_sweep_directory(plan_inputs.out_dir, std::cerr);
      experiments::SweepPlan plan = experiments::make_sweep_plan(plan_inputs);
      experiments::prepare_sweep_directory(plan_inputs, plan);
      status = experiments::run_sweep_locally(std::move(plan), plan_inputs.out_dir, launch);
    } catch (const ConfigError& e) {
      throw py::value_error(e.what());
    }
  }
  const std::string sweep_dir = plan_inputs.out_dir.string();
  if (pending) {
    const py::object exception = pending->value();
    try {
      py::setattr(exception, "bsg_sweep_dir", py::str(sweep_dir));
      if (py::hasattr(exception, "add_note")) {
        exception.attr("add_note")("bsg.sweep: the running runs stopped with a checkpoint; run bsg.sweep again on " +
                                   sweep_dir + " to resume");
      }
    } catch (const py::error_already_set&) {
      // An exception type that takes no attributes keeps its own message only.
    }
    throw *pending;
  }
  if (status != 0) {
    throw std::runtime_error("bsg.sweep: runs of " + sweep_dir +
                             " failed (listed on stderr with their logs); run bsg.sweep again to retry them");
  }
  return sweep_dir;
}

}  // namespace

void bind_sweep(py::module_& module) {
  module.def(
      "sweep",
      [](std::string grid_file, std::optional<std::string> out, std::optional<std::string> configs, int jobs,
         int ranks_per_run, std::vector<std::string> only_env_ids, std::vector<std::string> only_algorithms,
         std::string program, std::string package_dir) {
        return sweep(SweepRequest{std::move(grid_file), std::move(out), std::move(configs), jobs, ranks_per_run,
                                  std::move(only_env_ids), std::move(only_algorithms), std::move(program),
                                  std::move(package_dir)});
      },
      py::arg("grid_file"), py::arg("out"), py::arg("configs"), py::arg("jobs"), py::arg("ranks_per_run"),
      py::arg("env"), py::arg("alg"), py::arg("program"), py::arg("package_dir"));
  // Where the bsg program lies relative to the installed package, and where the build tree's is
  // (python/CMakeLists.txt); bsg.sweep takes the first that exists.
  module.attr("program_from_package") = BSG_PROGRAM_FROM_PACKAGE;
  module.attr("build_tree_program") = BSG_BUILD_TREE_PROGRAM;
}

}  // namespace bsg::python
