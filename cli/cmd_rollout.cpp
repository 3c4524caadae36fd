// `bsg rollout --env ID --policy random|zero --episodes N --seed S
// [--physics faithful|lean] [--set key=value]... [--json]`:
// plays whole episodes with a fixed policy and prints each episode's return,
// cost and length, then their mean and standard deviation. The first episode
// resets with `seed`, later ones continue the environment's random stream; the
// random policy draws uniformly in [−1, 1] from its own generator seeded with S.
// --set changes a parameter of the environment's description (`bsg envs
// --describe ID` lists them); the JSON then also holds the overrides.
// --video FILE.mp4 and --trajectories FILE.png record the episodes (cli/recording.h).
#include <CLI/CLI.hpp>

#include <cmath>
#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "commands.h"
#include "common/random.h"
#include "env_set_arguments.h"
#include "envs/env.h"
#include "recording.h"

namespace bsg::cli {
namespace {

struct RolloutArguments {
  std::string env_id;
  std::string policy = "random";
  int episodes = 1;
  std::uint64_t seed = 0;
  std::string physics = "faithful";
  bool json = false;
  RecordingArguments recording;
  std::vector<std::string> set_arguments;  // environment overrides key=value
};

struct Episode {
  double episode_return = 0;
  double cost = 0;
  int length = 0;
};

struct MeanStd {
  double mean = 0;
  double std = 0;  // population standard deviation
};

template <typename Field>
MeanStd mean_std(const std::vector<Episode>& episodes, Field field) {
  MeanStd result;
  for (const Episode& e : episodes) result.mean += field(e);
  result.mean /= static_cast<double>(episodes.size());
  for (const Episode& e : episodes) result.std += std::pow(field(e) - result.mean, 2);
  result.std = std::sqrt(result.std / static_cast<double>(episodes.size()));
  return result;
}

int rollout(const RolloutArguments& args) {
  const envs::EnvOverrides overrides = parse_env_set_arguments(args.set_arguments);
  std::unique_ptr<envs::Env> env =
      envs::make(envs::describe(args.env_id, overrides),
                 {.physics = envs::parse_physics_model(args.physics)});
  std::optional<Recording> recording;
  if (args.recording.any()) {
    recording.emplace(args.recording);
    env = recording->wrap(std::move(env));
  }
  const int action_dim = env->spec().action_dim;
  const std::string env_name = env->spec().id;  // a custom description's own name; env is gone after a recording
  Rng policy_rng(args.seed ^ 0x9e3779b97f4a7c15ULL);  // independent of the env's stream
  std::vector<double> action(static_cast<size_t>(action_dim), 0.0);
  std::vector<Episode> episodes;
  for (int k = 0; k < args.episodes; ++k) {
    if (k == 0) {
      env->reset(args.seed);
    } else {
      env->reset();
    }
    Episode episode;
    bool done = false;
    while (!done) {
      if (args.policy == "random") {
        for (double& a : action) a = uniform(policy_rng, -1, 1);
      }
      const envs::StepResult step = env->step(action);
      episode.episode_return += step.reward;
      episode.cost += step.cost;
      ++episode.length;
      done = step.terminated || step.truncated;
    }
    episodes.push_back(episode);
  }
  if (recording) {
    env = nullptr;  // destroying the observed env lets the recorders finish the last episode
    recording->finish(args.json ? std::cerr : std::cout);
  }
  const MeanStd ret = mean_std(episodes, [](const Episode& e) { return e.episode_return; });
  const MeanStd cost = mean_std(episodes, [](const Episode& e) { return e.cost; });
  const MeanStd length = mean_std(episodes, [](const Episode& e) { return double(e.length); });
  if (args.json) {
    nlohmann::json out = {{"env", args.env_id},
                          {"policy", args.policy},
                          {"seed", args.seed},
                          {"physics", args.physics}};
    for (const auto& [key, value] : overrides) out["overrides"][key] = value;
    for (const Episode& e : episodes) {
      out["episodes"].push_back(
          {{"return", e.episode_return}, {"cost", e.cost}, {"length", e.length}});
    }
    out["mean"] = {{"return", ret.mean}, {"cost", cost.mean}, {"length", length.mean}};
    out["std"] = {{"return", ret.std}, {"cost", cost.std}, {"length", length.std}};
    std::cout << std::setprecision(17) << out.dump(2) << "\n";
    return 0;
  }
  std::cout << env_name << ", policy " << args.policy << ", seed " << args.seed << ", physics "
            << args.physics << "\n"
            << std::setw(8) << "episode" << std::setw(14) << "return" << std::setw(10) << "cost"
            << std::setw(8) << "length" << "\n";
  std::cout << std::fixed << std::setprecision(3);
  for (size_t k = 0; k < episodes.size(); ++k) {
    std::cout << std::setw(8) << k << std::setw(14) << episodes[k].episode_return << std::setw(10)
              << episodes[k].cost << std::setw(8) << episodes[k].length << "\n";
  }
  std::cout << "mean return " << ret.mean << " (std " << ret.std << "), mean cost " << cost.mean
            << " (std " << cost.std << "), mean length " << length.mean << " (std " << length.std
            << ")\n";
  return 0;
}

}  // namespace

void add_rollout_command(CLI::App& app, Action& run) {
  CLI::App* command = app.add_subcommand(
      "rollout", "Play episodes with a random or zero policy and print return, cost and length");
  auto args = std::make_shared<RolloutArguments>();
  command->add_option("--env", args->env_id, "environment id (see `bsg envs`)")->required();
  command->add_option("--policy", args->policy, "random (uniform in [-1, 1]) or zero")
      ->check(CLI::IsMember({"random", "zero"}));
  command->add_option("--episodes", args->episodes, "number of episodes (>= 1)")
      ->check(CLI::Range(1, 1000000));
  command->add_option("--seed", args->seed, "seed of the first reset and of the random policy");
  command->add_option("--physics", args->physics, "physics model: faithful (default) or lean")
      ->check(CLI::IsMember({"faithful", "lean"}));
  command->add_option("--set", args->set_arguments,
                      "change a parameter of the environment (repeatable), e.g. --set bombs=12")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  command->add_flag("--json", args->json, "print JSON with every episode and the summary");
  add_recording_options(*command, args->recording);
  command->callback([&run, args]() { run = [args]() { return rollout(*args); }; });
}

}  // namespace bsg::cli
