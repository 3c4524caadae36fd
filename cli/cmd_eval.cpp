// `bsg eval DIR [--episodes N] [--json] [--actions mean|sampled]`: the evaluation of a
// run directory's latest checkpoint (the mean action, or sampled as the config's
// sampled_evaluation or --actions says); prints J (mean return) and H (mean cost),
// with --json also every episode's figures. --video FILE.mp4 and
// --trajectories FILE.png record the episodes (cli/recording.h; one process only).
// A multi-agent run (docs/multi_agent.md#learners): its family's final evaluation, J and H the
// agents' mean and each agent's own below them (recorded alike; --actions sampled is refused).
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
    const algos::RunDirectory directory(args.run_dir);
    std::optional<algos::EvaluationActions> actions;
    if (args.actions) actions = *args.actions == "sampled" ? algos::EvaluationActions::sampled : algos::EvaluationActions::mean;
    // Before the recording opens its files.
    algos::check_multi_agent_evaluation(directory, actions == algos::EvaluationActions::sampled);
    std::optional<Recording> recording;
    if (args.recording.any()) recording.emplace(args.recording);
    algos::EnvDecorator record;  // none unless asked for
    algos::MultiAgentEnvDecorator record_multi_agent;
    if (recording) {
      record = [&](std::unique_ptr<envs::Env> env) { return recording->wrap(std::move(env)); };
      record_multi_agent = [&](std::unique_ptr<envs::MultiAgentEnv> env) { return recording->wrap(std::move(env)); };
    }
    const algos::RunEvaluation result = algos::evaluate_run_directory(directory, args.episodes, mpi, record, actions,
                                                                      std::nullopt, record_multi_agent);
    if (recording) recording->finish(args.json ? std::cerr : std::cout);
    if (!mpi.is_root()) return 0;
    if (args.json) {
      std::cout << algos::evaluation_json(result.summary, true);
    } else {
      if (result.epochs_completed < result.epochs) {
        std::cout << "note: the checkpoint covers " << result.epochs_completed << " of " << result.epochs
                  << " epochs (the run is not finished)\n";
      }
      const algos::EvaluationSummary& summary = result.summary;
      std::cout << "episodes " << summary.episodes.size() << "\n"
                << "J (mean return) " << algos::format_csv_number(summary.mean_return) << "\n"
                << "H (mean cost) " << algos::format_csv_number(summary.mean_cost) << "\n";
      // A multi-agent run: J and H are the agents' mean; each agent's own follows.
      for (std::size_t a = 0; a < summary.mean_agent_returns.size(); ++a) {
        std::cout << "agent_" << a << " J (mean return) " << algos::format_csv_number(summary.mean_agent_returns[a])
                  << " H (mean cost) " << algos::format_csv_number(summary.mean_agent_costs[a]) << "\n";
      }
      std::cout << "mean length " << algos::format_csv_number(summary.mean_length) << "\n"
                << "actions " << (summary.action_std > 0.0
                                      ? "sampled, sigma " + algos::format_csv_number(summary.action_std)
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
