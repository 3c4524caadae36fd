// `bsg train`: resolve a run's configuration, train, evaluate.
//   bsg train CONFIG [--set key=value]... [--out DIR] [--configs DIR]
//   bsg train --print-config CONFIG [--set key=value]...
//   bsg train --resume DIR
// Under `mpirun -np N` the batch is split over the N ranks (the same code runs
// with one process and no MPI).
// --print-config runs every check training runs before it (check_before_training).
// SIGTERM, SIGINT, SIGHUP or SIGUSR1 (scancel, a preemption, Ctrl-C, a closed terminal) stops the run at
// the end of the current epoch with a checkpoint and exit code 75
// (stop_signals.h); under mpirun a signal reaching any rank stops all of them
// at the same epoch (send mpirun SIGUSR1: it forwards that one at once).
#include <CLI/CLI.hpp>

#include <iostream>
#include <memory>
#include <stdexcept>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "algos/training/run_directory.h"
#include "algos/training/run_start.h"
#include "commands.h"
#include "common/config_error.h"
#include "common/mpi_context.h"
#include "common/run_config_resolve.h"
#include "common/run_config_yaml.h"
#include "configs_search.h"
#include "mpi_abort_on_error.h"
#include "stop_signals.h"

namespace bsg::cli {
namespace {

struct TrainArguments {
  std::string config_file;
  std::vector<std::string> set_arguments;
  std::string out_dir;
  std::string configs_dir;
  std::string resume_dir;
  bool print_config = false;
  int stop_after_epochs = 0;
  bool quiet = false;
};

struct ResolvedTrainConfig {
  RunConfig config;
  LocatedConfigs configs;  // the folder the run file was resolved against
};

ResolvedTrainConfig resolve_config(const TrainArguments& args) {
  if (!args.config_file.empty() && !std::filesystem::is_regular_file(args.config_file)) {
    throw ConfigError("run file " + args.config_file + " does not exist");
  }
  ResolvedTrainConfig resolved;
  resolved.configs = find_configs(args.configs_dir, args.config_file, "run file");
  RunConfigRequest request;
  request.configs_dir = resolved.configs.dir;
  request.run_file = args.config_file;
  request.set_arguments = args.set_arguments;
  resolved.config = algos::resolve_training_config(std::move(request));
  return resolved;
}

int train(const TrainArguments& args) {
  if (args.print_config) {
    const ResolvedTrainConfig resolved = resolve_config(args);
    algos::check_before_training(resolved.config, 1);
    // A YAML comment, so that the output stays a valid run file.
    std::cout << "# " << describe_configs(resolved.configs) << "\n" << to_run_file_yaml(resolved.config);
    return 0;
  }
  const StopSignals stop_signals;  // before MPI starts its threads: they inherit the mask
  MpiSession session;
  const MpiContext mpi = session.context();
  return run_or_abort_job(mpi, [&]() {
    const bool resume = !args.resume_dir.empty();
    RunConfig config;
    std::optional<LocatedConfigs> configs;
    std::optional<algos::RunDirectory> directory;
    if (resume) {
      directory.emplace(args.resume_dir);
      config = algos::resumed_training_config(*directory);
    } else {
      ResolvedTrainConfig resolved = resolve_config(args);
      config = std::move(resolved.config);
      configs = std::move(resolved.configs);
      directory.emplace(args.out_dir.empty() ? algos::default_run_directory(config) : std::filesystem::path(args.out_dir));
    }
    algos::check_before_training(config, mpi.size());

    algos::TrainerOptions options;
    options.resume = resume;
    options.stop_after_epochs = args.stop_after_epochs;
    options.log = args.quiet ? nullptr : &std::cout;
    // Collective: a signal that reached one rank stops every rank.
    options.stop_requested = [&stop_signals, &mpi] {
      return mpi.max(stop_signals.stop_pending() != 0 ? 1.0 : 0.0) > 0.0;
    };
    if (mpi.is_root() && !args.quiet) {
      std::string env_name = config.env_id;
      for (const auto& [key, value] : config.env) {
        if (key == "name" && value != config.env_id) env_name = value + " (from " + config.env_id + ")";
      }
      // An offline epoch takes gradient steps on its dataset, no environment step.
      const std::string epoch_work = is_offline(config.alg) ? std::to_string(config.offline.updates_per_epoch) +
                                                                  " gradient steps on " + config.offline.dataset
                                                            : std::to_string(config.steps_per_epoch) + " steps";
      std::cout << "bsg train: " << env_name << " " << to_string(config.alg) << " seed " << config.seed << ", "
                << config.epochs << " epochs of " << epoch_work << " on " << mpi.size()
                << (mpi.size() == 1 ? " rank" : " ranks") << (resume ? ", resuming " : " -> ")
                << directory->root.string() << std::endl;
      if (configs) std::cout << describe_configs(*configs) << std::endl;
    }
    const algos::TrainingOutcome outcome = algos::allocate_trainer(config, *directory, mpi, options)->run();
    if (mpi.is_root() && !outcome.finished) {
      (outcome.stop_requested ? std::cerr : std::cout)
          << (outcome.stop_requested ? "bsg train: stop signal received: " : "") << "stopped after "
          << outcome.epochs_completed << " of " << config.epochs
          << " epochs; continue with: bsg train --resume " << directory->root.string() << std::endl;
    }
    return outcome.stop_requested ? kExitStoppedBySignal : 0;
  });
}

}  // namespace

void add_train_command(CLI::App& app, Action& run) {
  CLI::App* command = app.add_subcommand("train", "Train a policy: bsg train CONFIG [--set key=value]... [--out DIR]");
  command->footer(
      "SIGTERM, SIGINT, SIGHUP or SIGUSR1 stops training at the end of the current epoch, after a checkpoint, with "
      "exit code 75 (all ranks if any rank gets it; under mpirun send SIGUSR1, which mpirun forwards at once); "
      "continue with --resume DIR.");
  auto args = std::make_shared<TrainArguments>();
  command->add_option("CONFIG", args->config_file, "run file (YAML) naming env_id and alg; see configs/README.md");
  command->add_option("--set", args->set_arguments, "override one key: --set key=value (repeatable)")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  auto* out = command->add_option("--out", args->out_dir,
                                  "run directory (default: <log_dir>/<env_id>/<alg>/seed_<seed>)");
  command->add_option("--configs", args->configs_dir,
                      "configs folder (default: the first found at or above the run file's folder, at or above the "
                      "current folder, in $BSG_CONFIGS, installed, in the source tree)");
  auto* print = command->add_flag("--print-config", args->print_config,
                                  "print the fully resolved configuration and exit");
  auto* resume = command->add_option("--resume", args->resume_dir, "continue the run in this directory");
  command->add_option("--stop-after", args->stop_after_epochs,
                      "stop after this many epochs in total (with a checkpoint; continue with --resume)")
      ->check(CLI::NonNegativeNumber);
  command->add_flag("--quiet", args->quiet, "no progress lines");
  resume->excludes(out)->excludes(print);
  command->callback([&run, args]() {
    const bool has_config = !args->config_file.empty() || !args->set_arguments.empty();
    if (!args->resume_dir.empty() && has_config) {
      throw CLI::ValidationError("--resume", "takes the configuration from the run directory; give no CONFIG or --set");
    }
    if (args->resume_dir.empty() && !has_config) {
      throw CLI::RequiredError("CONFIG (or --resume DIR)");
    }
    run = [args]() { return train(*args); };
  });
}

}  // namespace bsg::cli
