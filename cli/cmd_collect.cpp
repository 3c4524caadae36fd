// `bsg collect --out FILE.hdf5 [--env ID] [--set key=value]... --policy SPEC...
// (--episodes N | --transitions N) [--seed S] [--actions sampled|mean]
// [--cost-limit K] [--physics faithful|lean] [--force]`: rolls policies out into
// an offline dataset in DSRL's HDF5 layout (docs/datasets.md#collecting).
// SPEC is `random` or a run directory, optionally with `=SHARE` (a relative
// weight, default 1): `--policy random=1 --policy runs/ppo_lag=3` gives the
// run's policy three quarters of the episodes. Without --env the environment
// is the first checkpoint's; every checkpoint must have been trained on the
// collection's environment (id and parameters). The rules are
// algos/training/collection_request.h; this file reads the arguments into a
// request and prints its summary.
#include <CLI/CLI.hpp>

#include <cstdint>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "algos/training/collection_request.h"
#include "commands.h"
#include "env_set_arguments.h"

namespace bsg::cli {
namespace {

// The command line as given; algos/training/collection_request.h has the rules.
struct CollectArguments {
  std::string out;
  std::string env_id;
  std::vector<std::string> set_arguments;
  std::vector<std::string> policies;  // "random" or a run directory, optionally "=SHARE"
  std::optional<std::int64_t> episodes;
  std::optional<std::int64_t> transitions;
  std::uint64_t seed = 0;
  std::string actions = "sampled";
  std::optional<double> cost_limit;
  std::string physics = "faithful";
  bool force = false;
};

int collect(const CollectArguments& args) {
  algos::CollectionRequest request;
  request.out = args.out;
  request.env_id = args.env_id;
  request.env_overrides = parse_env_set_arguments(args.set_arguments);
  for (const std::string& text : args.policies) request.policies.push_back(algos::parse_policy_spec(text));
  request.episodes = args.episodes;
  request.transitions = args.transitions;
  request.seed = args.seed;
  request.actions = args.actions == "mean" ? algos::EvaluationActions::mean : algos::EvaluationActions::sampled;
  request.cost_limit = args.cost_limit;
  request.physics = parse_physics_model(args.physics);
  request.force = args.force;
  const algos::CollectionSummary summary = algos::collect_to_file(request);
  std::cout << "wrote " << args.out << ": " << summary.transitions << " transitions, " << summary.episodes
            << " episodes of " << summary.env_id << " in " << summary.seconds << " s (" << summary.bytes
            << " bytes)\n";
  return 0;
}

}  // namespace

void add_collect_command(CLI::App& app, Action& run) {
  CLI::App* command = app.add_subcommand(
      "collect", "Roll policies out into an offline dataset (DSRL's HDF5 layout): bsg collect --out FILE --policy ...");
  auto args = std::make_shared<CollectArguments>();
  command->add_option("--out", args->out, "the HDF5 file to write")->required();
  command->add_option("--env", args->env_id, "environment id (default: the first checkpoint's)");
  command->add_option("--set", args->set_arguments, "change a parameter of --env's description (repeatable)")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  command
      ->add_option("--policy", args->policies,
                   "random or a run directory, optionally =SHARE (relative weight, default 1); repeatable")
      ->required()
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  command->add_option("--episodes", args->episodes, "episodes in all");
  command->add_option("--transitions", args->transitions, "transitions in all (the last episodes are cut)");
  command->add_option("--seed", args->seed, "seed of the environment resets and the policies' noise");
  command->add_option("--actions", args->actions, "checkpoints act with sampled (default) or mean actions")
      ->check(CLI::IsMember({"sampled", "mean"}));
  command->add_option("--cost-limit", args->cost_limit,
                      "the cost limit kappa stored for the normalised cost (default: the constraint's limit)")
      ->check(CLI::NonNegativeNumber);
  command->add_option("--physics", args->physics, "physics model: faithful (default) or lean")
      ->check(CLI::IsMember({"faithful", "lean"}));
  command->add_flag("--force", args->force, "replace an existing file");
  command->callback([&run, args]() { run = [args]() { return collect(*args); }; });
}

}  // namespace bsg::cli
