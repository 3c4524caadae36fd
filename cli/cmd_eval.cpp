// `bsg eval DIR [--episodes N] [--json] [--actions mean|sampled]`: the evaluation of a
// run directory's latest checkpoint (the mean action, or sampled as the config's
// sampled_evaluation or --actions says); prints J (mean return) and H (mean cost),
// with --json also every episode's figures. --video FILE.mp4 and
// --trajectories FILE.png record the episodes (cli/recording.h; one process only).
#include <CLI/CLI.hpp>

#include <iostream>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include "algos/training/evaluation_files.h"
#include "algos/training/progress_csv.h"
#include "algos/training/run_evaluation.h"
#include "commands.h"
#include "common/mpi_context.h"
#include "mpi_abort_on_error.h"
#include "recording.h"

namespace bsg::cli {
namespace {

struct EvalArguments {
  std::string run_dir;
  std::optional<int> episodes;
  std::optional<std::string> actions;  // "mean" or "sampled"; default: the config's sampled_evaluation
  bool json = false;
  RecordingArguments recording;
};

int evaluate(const EvalArguments& args) {
  MpiSession session;
  const MpiContext mpi = session.context();
  return run_or_abort_job(mpi, [&]() {
    if (args.recording.any() && mpi.size() > 1) {
      throw std::invalid_argument("--video and --trajectories record one process's episodes; run bsg eval without mpirun");
    }
    std::optional<Recording> recording;
    if (args.recording.any()) recording.emplace(args.recording);
    std::optional<algos::EvaluationActions> actions;
    if (args.actions) actions = *args.actions == "sampled" ? algos::EvaluationActions::sampled : algos::EvaluationActions::mean;
    const algos::RunEvaluation result = algos::evaluate_run_directory(
        algos::RunDirectory(args.run_dir), args.episodes, mpi,
        [&](std::unique_ptr<envs::Env> env) { return recording ? recording->wrap(std::move(env)) : std::move(env); },
        actions);
    if (recording) recording->finish(args.json ? std::cerr : std::cout);
    if (!mpi.is_root()) return 0;
    if (args.json) {
      std::cout << algos::evaluation_json(result.summary, true);
    } else {
      if (result.epochs_completed < result.epochs) {
        std::cout << "note: the checkpoint covers " << result.epochs_completed << " of " << result.epochs
                  << " epochs (the run is not finished)\n";
      }
      std::cout << "episodes " << result.summary.episodes.size() << "\n"
                << "J (mean return) " << algos::format_csv_number(result.summary.mean_return) << "\n"
                << "H (mean cost) " << algos::format_csv_number(result.summary.mean_cost) << "\n"
                << "mean length " << algos::format_csv_number(result.summary.mean_length) << "\n"
                << "actions " << (result.summary.action_std > 0.0
                                      ? "sampled, sigma " + algos::format_csv_number(result.summary.action_std)
                                      : std::string("mean (deterministic)"))
                << std::endl;
    }
    return 0;
  });
}

}  // namespace

void add_eval_command(CLI::App& app, Action& run) {
  CLI::App* command =
      app.add_subcommand("eval", "Evaluate a run's policy: bsg eval DIR [--episodes N] [--json] [--actions mean|sampled]");
  auto args = std::make_shared<EvalArguments>();
  command->add_option("DIR", args->run_dir, "run directory (holds config.yaml and checkpoint.bin)")->required();
  command->add_option("--episodes", args->episodes, "episodes in total (default: the config's eval_episodes)")
      ->check(CLI::NonNegativeNumber);
  command->add_flag("--json", args->json, "print JSON with every episode's return, cost and length");
  command
      ->add_option("--actions", args->actions,
                   "mean: the deterministic mean action; sampled: mu + sigma eps at the last epoch's sigma "
                   "(default: the run's sampled_evaluation)")
      ->check(CLI::IsMember({"mean", "sampled"}));
  add_recording_options(*command, args->recording);
  command->callback([&run, args]() { run = [args]() { return evaluate(*args); }; });
}

}  // namespace bsg::cli
