// `bsg dataset info FILE [--plot FILE.png] [--json]`: what an offline dataset
// holds (docs/datasets.md#reading): transitions, complete episodes (and how
// many the environment ended), the ranges of the episodes' reward and cost
// returns, how many keep within the stored cost limit, and how it was made.
// --plot draws each episode's cost return against its reward return, the
// stored cost limit dashed (DSRL's picture of a dataset's reward-cost frontier).
//
// `bsg dataset bc FILE --variant all|safe [--cost-limit K] [--seeds 0,1,2]
// [--updates N] [--batch-size B] [--hidden 256,256] [--learning-rate LR]
// [--eval-episodes N] [--json]`: behaviour cloning on the file (BC-All or
// BC-Safe, docs/datasets.md#behaviour-cloning), one policy per seed, each
// evaluated online on the file's environment (N episodes collected with the
// seed derive_seed(seed, evaluation_environment, 0), so not from the
// dataset's own starts) and scored with DSRL's normalised reward and cost.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "algos/offline/behaviour_cloning.h"
#include "algos/offline/collection.h"
#include "algos/offline/dataset_environment.h"
#include "algos/offline/dataset_file.h"
#include "algos/offline/normalized_score.h"
#include "commands.h"
#include "common/seeding.h"
#include "render/png_file.h"
#include "render/scatter_plot.h"

namespace bsg::cli {
namespace {

struct DatasetInfoArguments {
  std::string file;
  std::string plot;
  bool json = false;
};

struct Range {
  double min = 0.0, mean = 0.0, max = 0.0;
};

Range range_of(const std::vector<double>& values) {
  Range r;
  if (values.empty()) return r;
  r.min = *std::min_element(values.begin(), values.end());
  r.max = *std::max_element(values.begin(), values.end());
  for (double v : values) r.mean += v;
  r.mean /= static_cast<double>(values.size());
  return r;
}

int dataset_info(const DatasetInfoArguments& args) {
  const algos::OfflineDataset dataset = algos::read_dataset_file(args.file);
  const std::vector<algos::DatasetEpisode> episodes = algos::dataset_episodes(dataset);
  std::vector<double> rewards, costs;
  std::size_t terminated = 0;
  for (const algos::DatasetEpisode& e : episodes) {
    rewards.push_back(e.reward_return);
    costs.push_back(e.cost_return);
    terminated += e.terminated ? 1 : 0;
  }
  const Range reward = range_of(rewards);
  const Range cost = range_of(costs);
  const auto limit_attribute = dataset.number_attributes.find("cost_limit");
  const std::optional<double> cost_limit =
      limit_attribute == dataset.number_attributes.end() ? std::nullopt : std::optional(limit_attribute->second);
  const std::size_t within = cost_limit ? static_cast<std::size_t>(std::count_if(costs.begin(), costs.end(), [&](double c) {
    return c <= *cost_limit;
  }))
                                        : 0;
  const auto text = [&](const std::string& key) {
    const auto it = dataset.text_attributes.find(key);
    return it == dataset.text_attributes.end() ? std::string("(not recorded)") : it->second;
  };
  if (!args.plot.empty()) {
    render::ScatterPlotOptions options;
    options.x_label = "cost";
    options.y_label = "return";
    options.vertical_line = cost_limit;
    render::write_png(args.plot, render::scatter_plot(costs, rewards, options));
  }
  if (args.json) {
    nlohmann::json out = {{"file", args.file},
                          {"transitions", dataset.size()},
                          {"episodes", episodes.size()},
                          {"terminated_episodes", terminated},
                          {"observation_dim", dataset.observation_dim},
                          {"action_dim", dataset.action_dim},
                          {"reward_return", {{"min", reward.min}, {"mean", reward.mean}, {"max", reward.max}}},
                          {"cost_return", {{"min", cost.min}, {"mean", cost.mean}, {"max", cost.max}}},
                          {"constraints", dataset.constraint_names}};
    if (cost_limit) {
      out["cost_limit"] = *cost_limit;
      out["episodes_within_cost_limit"] = within;
    }
    for (const auto& [key, value] : dataset.text_attributes) out["attributes"][key] = value;
    for (const auto& [key, value] : dataset.number_attributes) out["attributes"][key] = value;
    std::cout << out.dump(2) << "\n";
    return 0;
  }
  std::cout << args.file << ": " << text("env_id") << ", made by bsg " << text("bsg_version") << "\n"
            << "transitions " << dataset.size() << ", complete episodes " << episodes.size() << " ("
            << terminated << " ended by the environment)\n"
            << "observations " << dataset.observation_dim << ", actions " << dataset.action_dim << "\n"
            << "reward return min " << reward.min << ", mean " << reward.mean << ", max " << reward.max << "\n"
            << "cost return min " << cost.min << ", mean " << cost.mean << ", max " << cost.max << "\n";
  if (cost_limit) {
    std::cout << "cost limit " << *cost_limit << ": " << within << " of " << episodes.size()
              << " episodes within it\n";
  }
  if (dataset.constraint_names.size() > 1) {
    std::cout << "constraints";
    for (const std::string& name : dataset.constraint_names) std::cout << " " << name;
    std::cout << "\n";
  }
  // One policy a line (algos/offline/collection.h), each indented under the heading.
  std::string policies = text("policies");
  for (std::size_t at = policies.find('\n'); at != std::string::npos; at = policies.find('\n', at + 3)) {
    policies.replace(at, 1, "\n  ");
  }
  std::cout << "policies:\n  " << policies << "\n";
  if (!args.plot.empty()) std::cout << "wrote " << args.plot << "\n";
  return 0;
}

struct BcArguments {
  std::string file;
  std::string variant = "all";
  std::optional<double> cost_limit;
  std::vector<std::uint64_t> seeds{0, 1, 2};
  int updates = 20000;
  int batch_size = 512;
  std::vector<int> hidden{256, 256};
  double learning_rate = 1e-3;
  int eval_episodes = 10;
  bool json = false;
};

double number_attribute(const algos::OfflineDataset& dataset, const std::string& file, const std::string& key) {
  const auto it = dataset.number_attributes.find(key);
  if (it == dataset.number_attributes.end()) {
    throw std::invalid_argument("dataset file " + file + ": no attribute " + key + " (not written by bsg collect?)");
  }
  return it->second;
}

int dataset_bc(const BcArguments& args) {
  if (args.eval_episodes < 1) throw std::invalid_argument("--eval-episodes must be at least 1");
  if (args.seeds.empty()) throw std::invalid_argument("--seeds names no seed");
  const algos::OfflineDataset dataset = algos::read_dataset_file(args.file);
  const double cost_limit = args.cost_limit.value_or(number_attribute(dataset, args.file, "cost_limit"));
  const double min_reward = number_attribute(dataset, args.file, "min_episode_reward");
  const double max_reward = number_attribute(dataset, args.file, "max_episode_reward");
  const envs::EnvDescription description = algos::dataset_env_description(dataset);
  const auto physics = dataset.text_attributes.find("physics");
  std::unique_ptr<envs::Env> env = envs::make(
      description, {.physics = envs::parse_physics_model(physics == dataset.text_attributes.end() ? "faithful"
                                                                                                   : physics->second)});
  algos::BehaviourCloningOptions options;
  options.safe_only = args.variant == "safe";
  options.cost_limit = cost_limit;
  options.hidden_sizes = args.hidden;
  options.updates = args.updates;
  options.batch_size = args.batch_size;
  options.learning_rate = args.learning_rate;
  const std::string name = options.safe_only ? "BC-Safe" : "BC-All";
  nlohmann::json out = {{"file", args.file}, {"variant", name}, {"cost_limit", cost_limit},
                        {"min_episode_reward", min_reward}, {"max_episode_reward", max_reward}};
  std::vector<double> rewards, costs;
  std::ostringstream table;  // printed at the end, so that an error is the only output
  if (!args.json) {
    table << name << " on " << args.file << " (" << description.name << "), cost limit " << cost_limit << "\n"
          << std::setw(6) << "seed" << std::setw(8) << "rows" << std::setw(12) << "loss" << std::setw(12)
          << "return" << std::setw(10) << "cost" << std::setw(12) << "norm. R" << std::setw(10) << "norm. C"
          << "\n";
  }
  for (std::uint64_t seed : args.seeds) {
    options.seed = seed;
    const algos::BehaviourCloningResult trained = algos::train_behaviour_cloning(dataset, options);
    const algos::OfflineDataset episodes = algos::collect_dataset(
        *env, {{trained.policy.get(), 1.0}},
        {algos::CollectionUnit::episodes, args.eval_episodes, derive_seed(seed, SeedStream::evaluation_environment, 0)});
    double reward = 0.0, cost = 0.0;
    const std::vector<algos::DatasetEpisode> split = algos::dataset_episodes(episodes);
    for (const algos::DatasetEpisode& e : split) reward += e.reward_return, cost += e.cost_return;
    reward /= static_cast<double>(split.size());
    cost /= static_cast<double>(split.size());
    const algos::NormalizedScore score = algos::normalized_score(reward, cost, cost_limit, min_reward, max_reward);
    rewards.push_back(score.reward);
    costs.push_back(score.cost);
    out["seeds"].push_back({{"seed", seed}, {"rows", trained.rows}, {"episodes", trained.episodes},
                            {"final_loss", trained.final_loss}, {"return", reward}, {"cost", cost},
                            {"normalized_reward", score.reward}, {"normalized_cost", score.cost}});
    if (!args.json) {
      table << std::setw(6) << seed << std::setw(8) << trained.rows << std::setw(12) << std::setprecision(4)
            << trained.final_loss << std::fixed << std::setprecision(3) << std::setw(12) << reward
            << std::setw(10) << cost << std::setw(12) << score.reward << std::setw(10) << score.cost
            << std::defaultfloat << "\n";
    }
  }
  const auto mean_std = [](const std::vector<double>& v) {
    double mean = 0.0, var = 0.0;
    for (double x : v) mean += x;
    mean /= static_cast<double>(v.size());
    for (double x : v) var += (x - mean) * (x - mean);
    return std::pair{mean, std::sqrt(var / static_cast<double>(v.size()))};
  };
  const auto [r_mean, r_std] = mean_std(rewards);
  const auto [c_mean, c_std] = mean_std(costs);
  out["normalized_reward"] = {{"mean", r_mean}, {"std", r_std}};
  out["normalized_cost"] = {{"mean", c_mean}, {"std", c_std}};
  if (args.json) {
    std::cout << out.dump(2) << "\n";
  } else {
    std::cout << std::fixed << std::setprecision(3) << "normalised reward " << r_mean << " (std " << r_std
              << "), normalised cost " << c_mean << " (std " << c_std << ") over " << rewards.size()
              << " seeds\n";
  }
  return 0;
}

}  // namespace

void add_dataset_command(CLI::App& app, Action& run) {
  CLI::App* command = app.add_subcommand("dataset", "Offline datasets: bsg dataset info FILE | bc FILE | make RECIPE");
  command->require_subcommand(1);
  CLI::App* info = command->add_subcommand(
      "info", "Transitions, episodes, return and cost ranges of a dataset file; --plot draws cost against return");
  auto args = std::make_shared<DatasetInfoArguments>();
  info->add_option("FILE", args->file, "an HDF5 dataset (bsg collect or DSRL)")->required();
  info->add_option("--plot", args->plot, "write the episodes' cost return against reward return as a PNG");
  info->add_flag("--json", args->json, "print JSON");
  info->callback([&run, args]() { run = [args]() { return dataset_info(*args); }; });

  CLI::App* bc = command->add_subcommand(
      "bc", "Behaviour cloning (BC-All or BC-Safe) on a dataset file, evaluated online with DSRL's normalised scores");
  auto bc_args = std::make_shared<BcArguments>();
  bc->add_option("FILE", bc_args->file, "an HDF5 dataset written by bsg collect")->required();
  bc->add_option("--variant", bc_args->variant, "all (BC-All, every row) or safe (BC-Safe, episodes within the limit)")
      ->check(CLI::IsMember({"all", "safe"}));
  bc->add_option("--cost-limit", bc_args->cost_limit, "kappa for BC-Safe and the normalised cost (default: the file's)")
      ->check(CLI::NonNegativeNumber);
  bc->add_option("--seeds", bc_args->seeds, "one policy per seed (default 0,1,2)")->delimiter(',');
  bc->add_option("--updates", bc_args->updates, "Adam steps (default 20000)")->check(CLI::PositiveNumber);
  bc->add_option("--batch-size", bc_args->batch_size, "rows per minibatch (default 512)")->check(CLI::PositiveNumber);
  bc->add_option("--hidden", bc_args->hidden, "hidden layer sizes (default 256,256)")->delimiter(',');
  bc->add_option("--learning-rate", bc_args->learning_rate, "Adam's learning rate (default 1e-3)")
      ->check(CLI::PositiveNumber);
  bc->add_option("--eval-episodes", bc_args->eval_episodes, "online evaluation episodes per seed (default 10)");
  bc->add_flag("--json", bc_args->json, "print JSON");
  bc->callback([&run, bc_args]() { run = [bc_args]() { return dataset_bc(*bc_args); }; });
  add_dataset_make_command(*command, run);
}

}  // namespace bsg::cli
