// `bsg bench [--env ID] [--steps N] [--json]`: environment steps per second on
// one core with random actions, beside the raw physics rate of the same world
// (actions and engine steps only, no task, sensor or observation work).
// `bsg bench --train --env ID --alg A [--epochs N] [--set key=value]... [--json]`:
// seconds per training epoch instead (train_benchmark.h).
#include <CLI/CLI.hpp>

#include <iomanip>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "commands.h"
#include "envs/env.h"
#include "envs/env_benchmark.h"
#include "train_benchmark.h"

namespace bsg::cli {
namespace {

struct BenchArguments {
  std::string env_id;  // empty: every registered environment
  long steps = 20000;
  bool json = false;
  bool train = false;  // --train: time training epochs (train_benchmark.h)
};

int bench(const BenchArguments& args) {
  std::vector<std::string> ids;
  if (args.env_id.empty()) {
    ids = envs::registered_ids();
  } else {
    envs::make(args.env_id);  // an unknown id fails here, listing the valid ones
    ids.push_back(args.env_id);
  }
  nlohmann::json list = nlohmann::json::array();
  if (!args.json) {
    std::cout << std::left << std::setw(24) << "id" << std::right << std::setw(14) << "env steps/s"
              << std::setw(18) << "physics steps/s" << std::setw(12) << "overhead" << "\n";
  }
  for (const std::string& id : ids) {
    const envs::EnvBenchmark result = envs::benchmark_env(id, args.steps);
    const double overhead = result.physics_steps_per_second / result.env_steps_per_second;
    if (args.json) {
      list.push_back({{"id", id},
                      {"steps", result.steps},
                      {"env_steps_per_second", result.env_steps_per_second},
                      {"physics_steps_per_second", result.physics_steps_per_second},
                      {"overhead", overhead}});
    } else {
      std::cout << std::left << std::setw(24) << id << std::right << std::fixed
                << std::setprecision(0) << std::setw(14) << result.env_steps_per_second
                << std::setw(18) << result.physics_steps_per_second << std::setprecision(2)
                << std::setw(11) << overhead << "x" << std::endl;
    }
  }
  if (args.json) std::cout << list.dump(2) << "\n";
  return 0;
}

}  // namespace

void add_bench_command(CLI::App& app, Action& run) {
  CLI::App* command = app.add_subcommand(
      "bench", "Env steps per second on one core, beside the raw physics rate of the same world");
  auto args = std::make_shared<BenchArguments>();
  command->add_option("--env", args->env_id, "one environment id (default: all registered)");
  auto* steps = command->add_option("--steps", args->steps, "steps per measurement (>= 1)")
                    ->check(CLI::Range(1L, 100000000L));
  command->add_flag("--json", args->json, "print a JSON array");
  // --train: seconds per training epoch (collection, policy update, value fits).
  auto train = std::make_shared<TrainBenchArguments>();
  auto* train_flag = command->add_flag("--train", args->train, "time training epochs instead of environment steps");
  auto* alg = command->add_option("--alg", train->alg, "--train: algorithm (default lag-trpo)");
  auto* epochs = command->add_option("--epochs", train->epochs, "--train: epochs to time (default 5)")
                     ->check(CLI::Range(1, 1000000));
  auto* set = command->add_option("--set", train->set_arguments, "--train: override one config key (repeatable)")
                  ->expected(1)
                  ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  steps->excludes(train_flag);
  alg->needs(train_flag);
  epochs->needs(train_flag);
  set->needs(train_flag);
  command->callback([&run, args, train]() {
    if (args->train) {
      if (!args->env_id.empty()) train->env_id = args->env_id;
      train->json = args->json;
      run = [train]() { return run_train_benchmark(*train); };
      return;
    }
    run = [args]() { return bench(*args); };
  });
}

}  // namespace bsg::cli
