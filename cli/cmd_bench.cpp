// `bsg bench [--env ID] [--steps N] [--physics M ...] [--rounds R] [--json]`:
// environment steps per second on one core with random actions, beside the raw
// physics rate of the same world (actions and engine steps only, no task,
// sensor or observation work). With several physics models (e.g. `--physics
// faithful lean`), each environment is measured with every model in turn, R
// times, alternating, so that a shared or throttled CPU affects all alike; the
// text output then ends with the ratio of the median rates to the first model's.
// `--set key=value` (repeatable) changes a parameter of the environment's
// description (`bsg envs --describe ID`); with --train it sets a run key instead.
// `bsg bench --train --env ID --alg A [--epochs N] [--set key=value]... [--json]`:
// seconds per training epoch instead (train_benchmark.h).
#include <CLI/CLI.hpp>

#include <algorithm>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "commands.h"
#include "env_set_arguments.h"
#include "envs/env.h"
#include "envs/env_benchmark.h"
#include "train_benchmark.h"

namespace bsg::cli {
namespace {

struct BenchArguments {
  std::string env_id;  // empty: every registered environment
  long steps = 20000;
  std::vector<std::string> physics = {"faithful"};
  int rounds = 1;
  bool json = false;
  bool train = false;  // --train: time training epochs (train_benchmark.h)
  std::vector<std::string> set_arguments;  // environment overrides key=value
};

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const size_t n = values.size();
  return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

int bench(const BenchArguments& args) {
  std::vector<envs::EnvOptions> models;
  for (const std::string& name : args.physics) {
    models.push_back({.physics = envs::parse_physics_model(name)});  // a bad name fails here
  }
  const envs::EnvOverrides overrides = parse_env_set_arguments(args.set_arguments);
  std::vector<envs::EnvDescription> descriptions;
  if (args.env_id.empty()) {
    // Overrides apply to every id that has the keys (a Gather key skips the others).
    for (const std::string& id : envs::registered_ids()) {
      if (overrides.empty()) {
        descriptions.push_back(envs::describe(id));
        continue;
      }
      bool applies = true;
      for (const auto& [key, value] : overrides) {
        const envs::EnvParameter* parameter = envs::find_env_parameter(key);
        applies = applies && (parameter == nullptr || envs::applies_to(*parameter, envs::describe(id)));
      }
      if (applies) descriptions.push_back(envs::describe(id, overrides));  // bad values fail here
    }
    if (descriptions.empty()) envs::describe("SafetyBallCircle-v0", overrides);  // names the key
  } else {
    descriptions.push_back(envs::describe(args.env_id, overrides));
    for (const envs::EnvOptions& options : models) {
      envs::make(descriptions.back(), options);  // an unknown id or model fails here, naming it
    }
  }
  const bool several = models.size() > 1 || args.rounds > 1;
  nlohmann::json list = nlohmann::json::array();
  if (!args.json) {
    std::cout << std::left << std::setw(24) << "id" << std::setw(10) << "physics" << std::right
              << std::setw(14) << "env steps/s" << std::setw(18) << "physics steps/s"
              << std::setw(12) << "overhead" << "\n";
  }
  for (const envs::EnvDescription& description : descriptions) {
    const std::string& id = description.name;
    std::map<size_t, std::vector<double>> env_rates;  // model index → env steps/s per round
    for (int round = 0; round < args.rounds; ++round) {
      for (size_t m = 0; m < models.size(); ++m) {
        if (models[m].physics == envs::PhysicsModel::kLean &&
            !envs::has_lean_model(description)) {
          continue;  // all environments: skip those without a lean model
        }
        const envs::EnvBenchmark result = envs::benchmark_env(description, args.steps, 0, models[m]);
        const double overhead = result.physics_steps_per_second / result.env_steps_per_second;
        env_rates[m].push_back(result.env_steps_per_second);
        const std::string physics(to_string(models[m].physics));
        if (args.json) {
          list.push_back({{"id", id},
                          {"physics", physics},
                          {"round", round},
                          {"steps", result.steps},
                          {"env_steps_per_second", result.env_steps_per_second},
                          {"physics_steps_per_second", result.physics_steps_per_second},
                          {"overhead", overhead}});
        } else {
          std::cout << std::left << std::setw(24) << id << std::setw(10) << physics << std::right
                    << std::fixed << std::setprecision(0) << std::setw(14)
                    << result.env_steps_per_second << std::setw(18)
                    << result.physics_steps_per_second << std::setprecision(2) << std::setw(11)
                    << overhead << "x" << std::endl;
        }
      }
    }
    if (!args.json && several && env_rates.contains(0)) {
      const double reference = median(env_rates.at(0));
      std::cout << "  median env steps/s over " << args.rounds << " round(s):";
      for (const auto& [m, rates] : env_rates) {
        std::cout << " " << to_string(models[m].physics) << " " << std::setprecision(0)
                  << median(rates) << " (" << std::setprecision(2) << median(rates) / reference
                  << "x)";
      }
      std::cout << std::endl;
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
  auto* physics = command->add_option("--physics", args->physics,
                                      "physics model(s): faithful (default) and/or lean, measured in turn")
                      ->check(CLI::IsMember({"faithful", "lean"}));
  auto* rounds = command->add_option("--rounds", args->rounds,
                                     "measure every model this many times, alternating (>= 1)")
                     ->check(CLI::Range(1, 1000));
  command->add_flag("--json", args->json, "print a JSON array");
  // --train: seconds per training epoch (collection, policy update, value fits).
  auto train = std::make_shared<TrainBenchArguments>();
  auto* train_flag = command->add_flag("--train", args->train, "time training epochs instead of environment steps");
  auto* alg = command->add_option("--alg", train->alg, "--train: algorithm (default lag-trpo)");
  auto* epochs = command->add_option("--epochs", train->epochs, "--train: epochs to time (default 5)")
                     ->check(CLI::Range(1, 1000000));
  command->add_option("--set", args->set_arguments,
                      "change an environment parameter (repeatable), e.g. --set bombs=12; with "
                      "--train: override one config key")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  steps->excludes(train_flag);
  physics->excludes(train_flag);  // --train takes the model from the config: --set physics=lean
  rounds->excludes(train_flag);
  alg->needs(train_flag);
  epochs->needs(train_flag);
  command->callback([&run, args, train]() {
    if (args->train) {
      if (!args->env_id.empty()) train->env_id = args->env_id;
      train->json = args->json;
      train->set_arguments = args->set_arguments;
      run = [train]() { return run_train_benchmark(*train); };
      return;
    }
    run = [args]() { return bench(*args); };
  });
}

}  // namespace bsg::cli
